// libFuzzer target: benchmark suite JSON (`glcollide bench --suite FILE`). Scenes stay text in a
// parsed suite (each configuration re-parses them), so this exercises the suite reader alone.
#include "fuzz_support.hpp"

#include "benchkit/suite.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(glcollide::fuzz::asText(data, size));
    glcollide::fuzz::expectOnlyGlcollideErrors([&] {
        (void)glcollide::benchkit::parseSuite(text, glcollide::fuzz::scratchDir(), "fuzz_suite.json");
    });
    return 0;
}
