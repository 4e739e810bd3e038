// libFuzzer target: scene JSON text. The scratch folder holds one small valid mesh of each kind
// (mesh.obj, mesh.msh, mesh.node/.ele), so mutated scenes that name them reach mesh loading too.
#include "fuzz_support.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace {

void copySeedMeshes() {
    const std::filesystem::path data = GLCOLLIDE_TEST_DATA_DIR "/mesh";
    const auto& dir = glcollide::fuzz::scratchDir();
    const auto opts = std::filesystem::copy_options::overwrite_existing;
    std::filesystem::copy_file(data / "seam_square.obj", dir / "mesh.obj", opts);
    std::filesystem::copy_file(data / "two_tets_v41.msh", dir / "mesh.msh", opts);
    std::filesystem::copy_file(data / "two_tets0.node", dir / "mesh.node", opts);
    std::filesystem::copy_file(data / "two_tets0.ele", dir / "mesh.ele", opts);
}

// Generators build what they are asked for: a valid 512^3-cell tet box is 800 million tets, which
// exhausts memory without being a defect. Such scenes are not parsed; the limit leaves every
// generator kind and every size check reachable (cloth 447 x 447, tet box 58^3 cells).
bool requestsHugeGenerator(const std::string& text) {
    constexpr double kMaxGeneratedNodes = 2.0e5;
    const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("objects") || !j["objects"].is_array()) return false;
    for (const auto& object : j["objects"]) {
        if (!object.is_object() || !object.contains("generator") || !object["generator"].is_object())
            continue;
        const auto& g = object["generator"];
        if (!g.contains("resolution") || !g["resolution"].is_array()) continue;
        double nodes = 1.0;
        for (const auto& r : g["resolution"])
            if (r.is_number()) nodes *= std::fabs(r.get<double>()) + 1.0;
        if (!(nodes <= kMaxGeneratedNodes)) return true;
    }
    return false;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool seeded = (copySeedMeshes(), true);
    (void)seeded;
    const std::string text(glcollide::fuzz::asText(data, size));
    if (requestsHugeGenerator(text)) return 0;
    glcollide::fuzz::expectOnlyGlcollideErrors(
        [&] { (void)glcollide::parseScene(text, glcollide::fuzz::scratchDir(), "fuzz.json"); });
    return 0;
}
