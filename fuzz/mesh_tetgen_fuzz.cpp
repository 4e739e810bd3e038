// libFuzzer target: a TetGen .node/.ele pair loaded into a one-body scene. The input holds both
// files: the .node text, a NUL byte, the .ele text (no NUL: an empty .ele).
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace glcollide::fuzz;
    const std::string_view all = asText(data, size);
    const std::size_t split = all.find('\0');
    writeScratch("input.node", all.substr(0, split));
    writeScratch("input.ele", split == std::string_view::npos ? std::string_view{} : all.substr(split + 1));
    loadMeshScene("input.node");
    return 0;
}
