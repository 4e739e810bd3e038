// libFuzzer target: a .obj mesh loaded into a one-body scene (reader, topology, validation).
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    glcollide::fuzz::writeScratch("input.obj", glcollide::fuzz::asText(data, size));
    glcollide::fuzz::loadMeshScene("input.obj");
    return 0;
}
