// libFuzzer target: a .msh mesh loaded into a one-body scene (reader, topology, validation).
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    glcollide::fuzz::writeScratch("input.msh", glcollide::fuzz::asText(data, size));
    glcollide::fuzz::loadMeshScene("input.msh");
    return 0;
}
