// libFuzzer target: the triangle-pair CSV of `glcollide query tritri`.
#include "fuzz_support.hpp"

#include "scene/tri_pair_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    glcollide::fuzz::expectOnlyGlcollideErrors(
        [&] { (void)glcollide::parseTriPairCsv(glcollide::fuzz::asText(data, size), "fuzz.csv"); });
    return 0;
}
