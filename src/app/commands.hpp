#pragma once
// The subcommands of the glcollide CLI. Each returns the process exit code; setup errors are
// thrown as glcollide::Error and turned into one line on stderr by main().

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glcollide::app {

struct RunOptions {
    std::string scenePath;     ///< empty: the built-in default scene
    std::optional<int> frames; ///< overrides the scene's /time/frames
    std::string broadPhase;    ///< overrides the scene's /collision/broad_phase; empty: keep
    std::string exportDir;     ///< empty: no export
    int exportEvery = 1;
    std::string exportFormat = "obj";
    std::string statsPath; ///< empty: no statistics file
    std::string device;    ///< EGL device selector; empty: env or auto
    bool quiet = false;    ///< no progress on stderr
    bool gpuTiming = true;
    bool frameStep = false; ///< EngineOptions::frameStep
};

int runCommand(const RunOptions& options);

struct InfoOptions {
    std::string device;
    bool json = false;
};

int infoCommand(const InfoOptions& options);

struct QueryTriTriOptions {
    std::string inPath;               ///< CSV of triangle pairs (docs/narrow-phase.md)
    std::string outPath;              ///< empty: answers on stdout
    std::string precision = "robust"; ///< fast or robust
    std::string device;
};

/// glcollide query tritri: one line `1` (the closed triangles intersect) or `0` per data row.
int queryTriTriCommand(const QueryTriTriOptions& options);

/// The defaults of `query ccd`, equal to the pass's (checked in query_ccd_command.cpp).
inline constexpr int kQueryCcdDefaultBudget = 21844;
inline constexpr int kQueryCcdDefaultRounds = 4;

struct QueryCcdOptions {
    std::string inPath;                  ///< CSV of CCD queries, the CCD benchmark's layout (docs/ccd.md)
    std::string outPath;                 ///< empty: answers on stdout
    std::string kind;                    ///< vf (vertex-face) or ee (edge-edge)
    bool toi = false;                    ///< append ",<time of impact>" to each answer
    std::string minSeparation = "0";     ///< decimal, read exactly
    int budget = kQueryCcdDefaultBudget; ///< boxes per query and piece (passes::kDefaultCcdBudget)
    int rounds = kQueryCcdDefaultRounds; ///< continuation rounds (passes::kDefaultCcdContinuationRounds)
    std::string device;
};

/// glcollide query ccd: one line `1` (the primitives may come within the minimum separation during
/// [0, 1]) or `0` per query, with `--toi` followed by ",<time of impact>".
int queryCcdCommand(const QueryCcdOptions& options);

struct BenchOptions {
    std::string suite;                      ///< file, or "default" / "smoke" (built in); empty: default
    std::string outDir = "glcollide-bench"; ///< "{device}" is replaced by the renderer's slug
    std::vector<std::string> only;          ///< experiment names to run; empty: all
    std::optional<int> frames;              ///< overrides every experiment's measured frames
    std::string device;
    bool quiet = false;
};

/// glcollide bench: bench.json (Google Benchmark schema), report.md, headline.md and SVG plots
/// in the output folder, the table on stdout, progress on stderr.
int benchCommand(const BenchOptions& options);

struct RenderOptions {
    std::string scenePath;        ///< empty: the built-in default scene
    std::optional<int> frames;    ///< frames to simulate; overrides the scene's /time/frames
    std::string broadPhase;       ///< overrides the scene's /collision/broad_phase; empty: keep
    int every = 10;               ///< write frame 0 and every K-th frame
    std::string size = "800x600"; ///< WIDTHxHEIGHT in pixels
    int samples = 4;              ///< multisampling (0 or 1: none)
    bool flat = false;            ///< flat shading (one normal per face) instead of smooth
    std::string outDir = "glcollide-render";
    /// Non-empty: an MP4 (H.264 through the ffmpeg program) of every K-th frame at 1 / (K·dt)
    /// frames per second instead of PNGs; nothing else is written.
    std::string video;
    std::string device;
    bool quiet = false;
};

/// glcollide render: simulates headless and writes OUT/frame_NNNNNN.png snapshots drawn from the
/// engine's buffers (shaded bodies in distinct colours, intersecting faces in red, a ground grid).
int renderCommand(const RenderOptions& options);

struct ViewOptions {
    std::string scenePath;         ///< empty: the built-in default scene
    std::string broadPhase;        ///< overrides the broad phase of every scene opened; empty: keep
    std::string device;            ///< auto or software (a window's context comes from the window system)
    std::string size = "1280x800"; ///< the window's size in pixels
    std::optional<int> frames;     ///< run this many frames without a user, then exit
    std::string screenshot;        ///< with frames: write the window's last frame here (PNG)
    std::string input;             ///< a script of input events (docs/viewer.md)
};

/// glcollide view: a window running the engine in its own GL context, with a panel
/// (docs/viewer.md). Builds without GLFW or Dear ImGui have a view that says so and exits 1.
int viewCommand(const ViewOptions& options);

/// "WIDTHxHEIGHT", each 1 ... 16384, for `option` (e.g. "--size"); throws Error otherwise.
std::pair<int, int> parseSize(const std::string& text, const std::string& option = "--size");

} // namespace glcollide::app
