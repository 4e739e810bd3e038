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
    double milliseconds =
        0.0;               ///< CPU wall time of the build: cache look-up + load, or compile + link (+ store)
    bool cacheHit = false; ///< loaded from the program binary cache
};

/// What the on-device self-check of robust precision does on a disagreement with the exact oracle
/// (EngineOptions::robustSelfCheck; the environment variable GLCOLLIDE_SELF_CHECK=error|warn|off,
/// when set, wins): throw glcollide::Error, warn (Engine::warnings(), SelfCheckReport::message), or
/// not check at all.
enum class SelfCheckMode { Error, Warn, Off };

/// The on-device self-check of robust narrow-phase precision (docs/narrow-phase.md, "On-device
/// self-check"): the built-in hard and near-degenerate triangle pairs run through the robust query
/// on this device and are compared with the exact oracle, once per device, driver and shader.
struct SelfCheckReport {
    SelfCheckMode mode = SelfCheckMode::Error;
    bool needed = false;     ///< robust precision is used and the mode is not Off
    bool remembered = false; ///< a pass was remembered (marker file, or earlier in this process): nothing ran
    bool passed = false;
    std::uint32_t cases = 0;   ///< cases run on the device (0 when remembered)
    std::uint32_t wrong = 0;   ///< cases whose answer differs from the oracle
    std::string firstWrong;    ///< the first wrong case: index, name, 18 coordinates, expected, got
    double milliseconds = 0.0; ///< all of it: building the query programs, running, comparing
    std::string marker;        ///< the file remembering the pass, empty when none (cache off or not written)
    std::string message;       ///< the failure text (the Error's or the warning's), empty when passed
};

/// Setup cost of one engine. Collected per engine (never process-wide), so engines do not mix.
struct SetupStats {
    double compileLinkMilliseconds = 0.0; ///< sum of ProgramSetup::milliseconds
    std::uint32_t cacheHits = 0;
    std::uint32_t cacheMisses =
        0; ///< compiled from source (cache off, empty, stale, or not offered by the driver)
    /// The program cache folder, empty when the cache is off (docs/integration.md, "Program cache").
    std::string cacheFolder;
    /// Why the cache was off or could not be used, empty when it worked (never an error).
    std::string cacheNote;
    std::vector<ProgramSetup> programs;
    /// Run at construction when the scene's collisions use robust precision.
    SelfCheckReport robustSelfCheck;
};

} // namespace glcollide
