#pragma once
/// \file What setting an engine up cost: building its compute programs (compile + link, or a load
/// from the program binary cache). Engine::setupStats() returns it; `glcollide run --stats`
/// writes it as "setup".

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide {

/// One compute program built during setup.
struct ProgramSetup {
    std::string shader;               ///< embedded shader name (or a test program's label)
    std::vector<std::string> defines; ///< as passed ("NAME" or "NAME VALUE")
    std::uint64_t sourceHash = 0;     ///< 64-bit FNV-1a of the expanded source (tells shader versions apart)
    double milliseconds = 0.0;        ///< CPU wall time of the build: cache look-up + load, or compile + link (+ store)
    bool cacheHit = false;            ///< loaded from the program binary cache
};

/// Setup cost of one engine. Collected per engine (never process-wide), so engines do not mix.
struct SetupStats {
    double compileLinkMilliseconds = 0.0; ///< sum of ProgramSetup::milliseconds
    std::uint32_t cacheHits = 0;
    std::uint32_t cacheMisses = 0; ///< compiled from source (cache off, empty, stale, or not offered by the driver)
    /// The program cache folder, empty when the cache is off (docs/integration.md, "Program cache").
    std::string cacheFolder;
    /// Why the cache was off or could not be used, empty when it worked (never an error).
    std::string cacheNote;
    std::vector<ProgramSetup> programs;
};

} // namespace glcollide
