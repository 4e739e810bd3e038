// Without libFuzzer (gcc builds): runs a fuzz target once on every file named on the command
// line or found in the folders named, so the corpus and the saved regressions are replayed by
// ctest in every build. Arguments starting with '-' (libFuzzer flags) are ignored.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void runOne(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

} // namespace

int main(int argc, char** argv) {
    std::size_t ran = 0;
    for (int i = 1; i < argc; ++i) {
        const std::filesystem::path arg = argv[i];
        if (argv[i][0] == '-') continue;
        if (std::filesystem::is_directory(arg)) {
            for (const auto& entry : std::filesystem::recursive_directory_iterator(arg))
                if (entry.is_regular_file()) runOne(entry.path()), ++ran;
        } else {
            runOne(arg), ++ran;
        }
    }
    std::cout << "ran " << ran << " inputs\n";
    return ran > 0 ? 0 : 1;
}
