#pragma once
// The on-device self-check of robust narrow-phase precision (docs/narrow-phase.md, "On-device
// self-check"). Robust precision promises the exact rational oracle's answer on every input; that
// rests on the device executing the integer and float operations of the shaders as GLSL
// specifies. The first time robust precision is used on a device, the built-in hard cases and a
// fixed sample of the near-degenerate random families run through both sets of robust kernels —
// the collision pipeline's (NarrowPhaseBatch: tri_tri_filtered, tri_tri_exact, the kernels engines
// run) and the query's (TriTriQueryPass: tri_tri_query_filtered, tri_tri_query_exact) — and are
// compared with the oracle. A disagreement is an Error (or a warning, or nothing, as the mode
// says) naming the device, the driver and the first wrong case. A pass is remembered per device,
// driver, the sources of every program it ran and the case set: a marker file in the program cache folder
// (across processes) and a set of keys in this process (when the cache is off), so the check runs once. Part
// of the engine (which runs it before robust collisions), not of passes: it needs the exact oracle and its
// cases (cpu/oracle/), and passes links no GMP.

#include "cpu/oracle/tri_tri_cases.hpp"

#include <glcollide/setup_stats.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::engine {

/// One case: a named pair; the expected answer comes from the oracle when the check runs.
struct SelfCheckCase {
    std::string name;
    cpu::FloatTriPair pair;
};

/// Pairs sampled from each of the ulp, scaled and degenerate random families, and their seed.
inline constexpr std::size_t kSelfCheckSamplePerFamily = 200;
inline constexpr std::uint32_t kSelfCheckSeed = 20261124u;

/// cpu::hardTriTriCases() (330) followed by the seeded samples (3 x kSelfCheckSamplePerFamily).
/// Built once per process; immutable.
const std::vector<SelfCheckCase>& builtinSelfCheckCases();

/// "error", "warn" or "off"; anything else throws Error naming `what` (the option or variable).
SelfCheckMode parseSelfCheckMode(std::string_view text, std::string_view what);
const char* toString(SelfCheckMode mode);
/// The mode in force: GLCOLLIDE_SELF_CHECK when set (it wins, so a user can relax the check of
/// a program they cannot rebuild), else `option`. A bad value of the variable throws Error.
SelfCheckMode effectiveSelfCheckMode(SelfCheckMode option);

/// Test hook: the expected answers of these case indices are inverted before comparing, so the
/// check (which still runs every case on the device) finds exactly these disagreements. Also
/// enters the remembered key, so an injected run never shares a marker with a real one.
struct SelfCheckInjection {
    std::vector<std::size_t> invertExpected;
};

/// The answers of one set of kernels to builtinSelfCheckCases(), in case order.
struct SelfCheckAnswers {
    std::string kernels;                 ///< names the kernels in messages, e.g. "collision kernels"
    std::vector<std::uint8_t> intersect; ///< 1: the closed triangles intersect
};

/// Compares every set of answers with the oracle (the expected answers of the injected cases
/// inverted) and fills report.cases, report.wrong (cases that some set answered differently)
/// and report.firstWrong (index, name, coordinates, expected, and what each wrong set said).
/// The device-free half of the check: tests feed it answers of simulated devices.
void judgeSelfCheckAnswers(const std::vector<SelfCheckAnswers>& answers, const SelfCheckInjection& injection,
                           SelfCheckReport& report);

/// Runs the check on the current context unless `mode` is Off or a pass is remembered. Throws
/// Error on a disagreement in Error mode; in Warn mode returns it in SelfCheckReport::message.
/// Programs it builds are recorded in the active SetupStats sink (gl/setup_stats_sink.hpp).
SelfCheckReport runRobustSelfCheck(SelfCheckMode mode, const SelfCheckInjection& injection = {});

/// Test hook: forgets the passes remembered in this process (marker files stay).
void forgetRememberedSelfChecks();

/// The 18 coordinates as "a0 (x, y, z) a1 (...) ... b2 (...)", each with 9 significant digits,
/// which names every float exactly (9 digits round-trip binary32).
std::string formatTriPair(const cpu::FloatTriPair& pair);

} // namespace glcollide::engine
