#include "fuzz_support.hpp"

#include <fstream>
#include <unistd.h>

namespace glcollide::fuzz {

namespace {

// Removed again when the process exits normally (a crashing input leaves it for inspection).
struct ScratchDir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("glcollide-fuzz-" + std::to_string(::getpid()));
    ScratchDir() { std::filesystem::create_directories(path); }
    ~ScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

} // namespace

const std::filesystem::path& scratchDir() {
    static const ScratchDir dir;
    return dir.path;
}

std::filesystem::path writeScratch(const std::string& name, std::string_view data) {
    const auto path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    return path;
}

void loadMeshScene(const std::string& meshName) {
    // A tet mesh rejects bend_stiffness and a surface mesh needs nothing else: the smallest body
    // that every mesh kind accepts.
    const std::string json = R"({"format_version": 1, "effects": ["springs"],
        "objects": [{"mesh": ")" +
                             meshName + R"(", "mass": 1, "springs": {"stiffness": 100}}]})";
    expectOnlyGlcollideErrors([&] { (void)parseScene(json, scratchDir(), "fuzz.json"); });
}

} // namespace glcollide::fuzz
