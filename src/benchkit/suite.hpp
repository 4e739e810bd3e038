#pragma once
/// \file A benchmark suite: which scenes `glcollide bench` runs, under which configurations, and
/// what each experiment measures (docs/benchmarks.md, "Suite files").

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glcollide::benchkit {

/// What an experiment measures; each kind has its own ground truth (docs/benchmarks.md).
enum class ExperimentKind {
    Scaling,     ///< time per frame against the number of faces, per pipeline (no ground truth)
    BroadPhase,  ///< missed intersecting pairs against the exact oracle on all face pairs
    NarrowPhase, ///< false positives / negatives of the triangle test against the exact oracle
    Integration, ///< trajectory error and energy drift against an analytic or converged solution
    Contact,     ///< deepest penetration and intersecting pairs left after the contact response
    Bvh,         ///< BVH vs octree on folded cloth and mesh scenes: per-pass times, equal candidates
                 ///< (bvh_experiment.hpp)
    Ccd,         ///< continuous collision queries against ground truth, beside Tight-Inclusion, and
                 ///< swept against discrete detection as an engine workload (ccd_experiment.hpp)
    Response,    ///< contact responses against step size: intersecting pairs (the exact TriTri),
                 ///< energy drift, safe-step cuts, solver iterations, time (response_experiment.hpp)
};

const char* kindName(ExperimentKind kind);

/// One scene of an experiment: scene-format JSON (inline or from a file) plus an optional JSON
/// merge patch (RFC 7386), kept as text so every configuration re-parses it with the scene
/// reader's own error messages.
struct SceneEntry {
    std::string name;
    std::string sceneJson;         ///< the scene document, merge patch already applied
    std::filesystem::path baseDir; ///< resolves the scene's mesh paths
    std::string source;            ///< "suite.json#/experiments/0/scenes/1" for messages
};

/// One configuration: a merge patch applied to every scene of the experiment, and a factor on
/// the scene's substep count (automatic or explicit).
struct ConfigEntry {
    std::string name;
    std::string patchJson = "{}";
    int substepFactor = 1; ///< >= 1
};

/// The reference an integration experiment measures trajectories against.
enum class IntegrationReference {
    Converged,  ///< the same scene at `referenceFactor` times the first configuration's substeps
    Ballistic,  ///< the closed form of free flight under gravity (springs at rest)
    Oscillator, ///< the closed form of one free node on one spring (damped harmonic oscillator)
};

/// The `bvh` kind's sizes and limits (docs/benchmarks.md, "The bvh experiment"). Its generated
/// scenes are the folded cloth of benchkit/folded_cloth.hpp at each size; `Experiment::scenes`
/// (optional for this kind) are further scenes, e.g. a mesh file, measured under `sceneConfigs`.
struct BvhSpec {
    std::vector<std::uint32_t> tableFaces; ///< laid out like the seed's Tables 1-3 (2,244 / 27,030 / 35,992)
    std::vector<std::uint32_t> scalingFaces; ///< the cost exponent is fitted over these
    std::uint32_t octreeMaxFaces = 0;        ///< octree configs skip generated cloths above this; 0: no limit
    int slowRunSeconds =
        0; ///< a non-BVH config slower than this per detection: 1 sample, no larger sizes; 0: off
    std::uint32_t cpuCheckMaxFaces =
        40000; ///< candidates also checked against the CPU brute force up to here
    int foldLayers =
        3; ///< layers of the folded cloth (3: ~15 candidates per face, 1M faces fit one 128 MiB list)
    std::string clothPatch =
        "{}"; ///< merge patch on the generated cloths' base scene (effects, thickness, dt)
    std::vector<std::string> engineConfigs; ///< configs also timed as Engine steps; empty: the bvh ones
    std::vector<std::string> sceneConfigs;  ///< configs run on `scenes`; empty: all
};

/// The `ccd` kind's query sets and parts (docs/benchmarks.md, "The ccd experiment").
struct CcdSpec {
    /// Query sets: "sample-queries" (every Sample-Queries file), "sample-queries unit-tests" (its
    /// unit-tests files only), "cloth-funnel", "cloth-ball" (listed pairs); each in vf and ee.
    std::vector<std::string> sets;
    std::vector<int> budgets;            ///< budget sweep on the first set (empty: none)
    std::vector<double> minSeparations;  ///< minimum-separation sweep (m) on the first set (empty: none)
    std::vector<int> scaleExponents;     ///< k of the 2^k scaling of every coordinate (empty: none)
    bool peer = true;                    ///< run Tight-Inclusion when its driver is there
    int peerTimeoutSeconds = 900;        ///< per driver call
    std::vector<std::string> engineSets; ///< steps timed as one detection: "cloth-funnel", "cloth-ball"
    double engineThickness = 1e-4;       ///< m, the detection's thickness on those steps
};

struct Experiment {
    ExperimentKind kind = ExperimentKind::Scaling;
    std::string name;  ///< unique in the suite; names output files
    std::string title; ///< one line for tables and plots
    std::vector<SceneEntry> scenes;
    std::vector<ConfigEntry> configs;
    int warmupFrames = 1; ///< frames stepped before measuring (shader compilation, list growth)
    int frames = 5;       ///< measured frames, >= 1
    IntegrationReference reference = IntegrationReference::Converged;
    int referenceFactor = 16;              ///< integration: reference substeps / first configuration's
    std::vector<std::string> caseFamilies; ///< narrow phase: triangle-pair families also measured
    BvhSpec bvh;                           ///< kind bvh only
    CcdSpec ccd;                           ///< kind ccd only
};

struct Suite {
    std::string name;
    std::string source; ///< file name or "built-in default suite"
    std::vector<Experiment> experiments;
};

/// Parses a suite (format in docs/benchmarks.md). Scene paths resolve relative to `baseDir`.
/// Throws glcollide::Error naming `sourceName` and the JSON pointer of what is wrong.
Suite parseSuite(const std::string& jsonText, const std::filesystem::path& baseDir,
                 const std::string& sourceName);
Suite loadSuite(const std::filesystem::path& path);

/// The suite `glcollide bench` runs without arguments: every accuracy axis and a scaling run up
/// to the paper's sizes, generated scenes only (no files needed), a few minutes on llvmpipe.
Suite defaultSuite();
/// The one-iteration suite CI runs (tiny scenes, every experiment kind).
Suite smokeSuite();

/// The triangle-pair families a narrow-phase experiment may name ("hard", "uniform", ...).
std::vector<std::string> knownCaseFamilies();

} // namespace glcollide::benchkit
