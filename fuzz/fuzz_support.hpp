#pragma once
// Shared by the libFuzzer targets (fuzz/*_fuzz.cpp): a private scratch folder per process, the
// file a reader is pointed at, and the rule for what counts as a finding.
//
// A reader may reject its input only with glcollide::Error (the CLI prints it as one clear
// message and exits 1). Anything else escaping — another exception type, a crash, a sanitizer
// report, a hang — is a finding: libFuzzer stops on it and saves the input.

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace glcollide::fuzz {

/// This process's scratch folder (created on first use, under the system temp directory).
const std::filesystem::path& scratchDir();

/// Writes `data` to scratchDir()/name and returns the path.
std::filesystem::path writeScratch(const std::string& name, std::string_view data);

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// Loads a one-body scene whose mesh is scratchDir()/meshName, as `glcollide run` would: reader,
/// tet orientation and boundary, springs, masses and validation all run. glcollide::Error is the
/// expected rejection and is swallowed; everything else propagates.
void loadMeshScene(const std::string& meshName);

/// Runs `f`, swallowing glcollide::Error only.
template <typename F> void expectOnlyGlcollideErrors(F&& f) {
    try {
        f();
    } catch (const glcollide::Error&) {
    }
}

} // namespace glcollide::fuzz
