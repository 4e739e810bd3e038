#include "benchkit/bvh_experiment.hpp"

#include "benchkit/folded_cloth.hpp"
#include "benchkit/report.hpp"

#include "cpu/collision_twin.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"
#include "passes/collision_detection.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace glcollide::benchkit {
namespace {

using json = nlohmann::json;
using Pairs = std::vector<std::array<std::uint32_t, 2>>;
using passes::PassId;

/// The bytes-per-face target of the BVH's own buffers (tree, sort, traversal state).
constexpr double kBytesPerFaceTarget = 192.0;
/// Feature pairs of one face pair without ownership: 3 + 3 vertex-face and 3 x 3 edge-edge.
constexpr double kFeaturePairsPerFacePair = 15.0;

/// The generated cloths' scene before the configuration's patch: dynamics with self-collisions,
/// a contact stiffness and dt for which the automatic substep rule gives a few substeps. The
/// placeholder body is replaced by the folded cloth; the scene reader validates everything else.
/// The penalty response with discrete detection: the pipeline whose broad phases this experiment
/// compares (its results since issue 16 were measured so).
const char* kClothScene = R"({"format_version": 1,
  "effects": ["gravity", "springs", "self_collisions"],
  "time": {"dt": 0.0001, "substeps": "auto"},
  "collision": {"thickness": 0.01, "stiffness": 100, "response": "penalty"},
  "objects": [{"name": "placeholder", "generator": {"type": "cloth", "size": [1, 1], "resolution": [2, 2]},
               "mass": 1, "springs": {"stiffness": 20}}]})";

/// 27030 -> "27,030".
std::string grouped(std::uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

/// A length in m, plainly ("0.008").
std::string metres(double v) {
    std::ostringstream s;
    s << std::setprecision(3) << v;
    return s.str();
}

/// Three significant digits (as the report prints numbers), "-" for NaN.
std::string ms(double v) {
    if (std::isnan(v)) return "-";
    std::ostringstream s;
    const double a = std::abs(v);
    if (a >= 1000)
        s << std::fixed << std::setprecision(0) << v;
    else if (a != 0 && a < 0.01)
        s << std::setprecision(2) << std::scientific << v;
    else
        s << std::setprecision(3) << v;
    return s.str();
}

bool isBvh(const Scene& s) {
    return s.collision.broadPhase == BroadPhase::Bvh;
}

/// A configuration's patch on `document`, then the scene reader (it validates the settings).
Scene parsePatched(json document, const ConfigEntry& c, const std::filesystem::path& baseDir,
                   const std::string& source) {
    document.merge_patch(json::parse(c.patchJson));
    return parseScene(document.dump(), baseDir, source + " (config \"" + c.name + "\")");
}

json clothDocument(const Experiment& x) {
    json document = json::parse(kClothScene);
    document.merge_patch(json::parse(x.bvh.clothPatch));
    return document;
}

/// What one scene is measured on: its model and, when configs differ only in settings, one cloth.
struct SceneInput {
    std::string name;
    std::uint32_t faces = 0;
    bool generated = false, inTable = false, inScaling = false;
    int layers = 0;                    ///< generated: layers of the fold
    std::optional<Body> cloth;         ///< generated: the folded cloth
    const SceneEntry* entry = nullptr; ///< a suite scene
};

Scene sceneFor(const Experiment& x, const SceneInput& in, const ConfigEntry& c) {
    if (!in.generated) {
        Scene scene = parsePatched(json::parse(in.entry->sceneJson), c, in.entry->baseDir, in.entry->source);
        if (scene.name.empty()) scene.name = in.name;
        return scene;
    }
    Scene scene = parsePatched(clothDocument(x), c, {}, "bvh experiment \"" + x.name + "\" cloth scene");
    scene.bodies = {*in.cloth};
    scene.name = in.name;
    validateScene(scene);
    return scene;
}

/// The collision settings a configuration gives the generated cloths.
CollisionSettings configSettings(const Experiment& x, const ConfigEntry& c) {
    return parsePatched(clothDocument(x), c, {}, "bvh experiment \"" + x.name + "\" cloth scene").collision;
}

/// Median of a pass's samples in a run (NaN when the run has no such pass).
double passMedian(const RunResult& r, PassId id) {
    for (std::size_t p = 0; p < r.passNames.size() && p < r.passMs.size(); ++p)
        if (r.passNames[p] == passes::passName(id)) return r.passMs[p].median;
    return std::nan("");
}

struct Detection {
    RunResult run;
    Pairs candidates;
    double firstSeconds = 0.0; ///< wall time of the first detection
    bool slow = false;         ///< measured once: the first detection exceeded slow_run_seconds
};

/// One configured scene: `warmup` detections, then `timed` ones, each its own GPU timer frame.
Detection measureDetection(const Experiment& x, const Scene& scene, const SceneInput& in,
                           const ConfigEntry& c, double slowSeconds) {
    Detection d;
    RunResult& r = d.run;
    r.scene = in.name;
    r.config = c.name;
    r.substeps = 1;
    try {
        const model::FlatModel model = model::flatten(scene);
        r.nodes = static_cast<std::uint32_t>(model.nodeCount());
        r.faces = static_cast<std::uint32_t>(model.faceCount());
        passes::CollisionConfig config;
        config.betweenObjects = scene.effects.has(Effect::Collisions);
        config.selfCollisions = scene.effects.has(Effect::SelfCollisions);
        config.settings = scene.collision;
        passes::CollisionDetection detection(config, model);
        passes::DeviceBuffers buffers;
        buffers.nodeCount = r.nodes;
        buffers.faceCount = r.faces;
        std::vector<glm::vec4> packed;
        packed.reserve(model.nodeCount());
        for (std::size_t n = 0; n < model.nodeCount(); ++n)
            packed.emplace_back(glm::vec3(model.positions[n]), static_cast<float>(model.inverseMasses[n]));
        buffers.positions = gl::makeBuffer("positions", packed);
        buffers.faces = gl::makeBuffer("faces", model.faceIndices);
        const std::vector<PassId> ids = detection.passes();
        r.passNames = detection.passNames();
        std::vector<std::vector<double>> samples(ids.size());
        std::vector<double> total, wall;
        gl::GpuTimer timer(passes::kPassCount);
        int warmup = x.warmupFrames, timed = x.frames;
        for (int i = 0; i < warmup + timed; ++i) {
            const auto start = std::chrono::steady_clock::now();
            timer.beginFrame();
            detection.detect(buffers, &timer);
            const std::vector<double> t = timer.resolveMilliseconds();
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (i == 0) {
                d.firstSeconds = seconds;
                if (slowSeconds > 0 && seconds > slowSeconds && !isBvh(scene)) {
                    d.slow = true; // one more detection, timed: the first may carry first-use costs
                    warmup = 1;
                    timed = 1;
                }
            }
            if (i < warmup) continue;
            double sum = 0.0;
            for (std::size_t p = 0; p < ids.size(); ++p) {
                samples[p].push_back(t[passes::passIndex(ids[p])]);
                sum += t[passes::passIndex(ids[p])];
            }
            total.push_back(sum);
            wall.push_back(1e3 * seconds);
        }
        for (auto& s : samples) r.passMs.push_back(summarize(s));
        r.gpuMs = summarize(total);
        r.wallMs = summarize(wall);
        r.frames = static_cast<int>(total.size());
        const passes::CollisionCounts& counts = detection.lastCounts();
        r.set("candidate_pairs", counts.candidates);
        r.set("intersecting_pairs", counts.intersections);
        if (counts.boxPairs) r.set("box_pairs", counts.boxPairs);
        if (isBvh(scene)) { // of the last timed detection
            r.set("bvh_rebuilt_last", counts.bvhRebuilt ? 1 : 0);
            r.set("bvh_traversal_rounds", counts.bvhRounds);
            r.set("bvh_node_visits", counts.bvhNodeVisits);
        }
        r.set("list_reruns_last", counts.reruns);
        // The Representative-Triangle expansion (FeaturePairs stage) of the last detection.
        r.set("vf_pairs_gpu", counts.vertexFacePairs);
        r.set("ee_pairs_gpu", counts.edgeEdgePairs);
        r.set("feature_pairs_gpu", double(counts.vertexFacePairs) + counts.edgeEdgePairs);
        r.set("feature_pairs_without_ownership_gpu",
              double(counts.vertexFacePairsWithoutOwnership + counts.edgeEdgePairsWithoutOwnership));
        r.set("broad_phase_bytes", static_cast<double>(detection.broadPhaseBytes()));
        r.set("broad_phase_bytes_per_face", static_cast<double>(detection.broadPhaseBytes()) / r.faces);
        r.set("octree_depth", isBvh(scene) ? 0 : scene.collision.octreeDepth);
        r.set("thickness_m", scene.collision.thickness);
        d.candidates = detection.readCandidates();
    } catch (const Error& e) {
        r.failure = e.what();
        return d;
    }
    // Broad phase = the broad phase's passes; detection = broad phase + TriTri (the feature-pair
    // expansion that follows is timed on its own); per pass medians as named metrics.
    double broad = 0.0, narrow = 0.0, features = 0.0;
    for (std::size_t p = 0; p < r.passNames.size(); ++p) {
        if (r.passNames[p] == passes::passName(PassId::TriTri))
            narrow += r.passMs[p].median;
        else if (r.passNames[p] == passes::passName(PassId::FeaturePairs))
            features += r.passMs[p].median;
        else
            broad += r.passMs[p].median;
    }
    r.set("broad_phase_ms", broad);
    r.set("detection_ms", broad + narrow);
    r.set("feature_pairs_ms", features);
    const std::pair<PassId, const char*> named[] = {
        {PassId::BvhBuild, "build_ms"},          {PassId::BvhRefit, "refit_ms"},
        {PassId::BvhTraverse, "traverse_ms"},    {PassId::BBUpdate, "bbupdate_ms"},
        {PassId::BBCollision, "bbcollision_ms"}, {PassId::TriTri, "tritri_ms"}};
    for (const auto& [id, key] : named)
        if (const double v = passMedian(r, id); !std::isnan(v)) r.set(key, v);
    r.time = broad + narrow;
    return d;
}

/// Whole Engine steps (dynamics + self-collision detection + contact response) of the scene.
RunResult measureEngine(const Experiment& x, const Scene& scene, const SceneInput& in, const ConfigEntry& c) {
    RunResult r;
    r.scene = in.name;
    r.config = c.name + " (engine step)";
    try {
        Engine engine(scene);
        r.nodes = engine.nodeCount();
        r.springs = engine.springCount();
        r.faces = engine.faceCount();
        r.substeps = engine.substepInfo().substeps;
        r.passNames = engine.pipeline();
        std::vector<std::vector<double>> samples(r.passNames.size());
        std::vector<double> total, wall;
        for (int frame = 0; frame < x.warmupFrames + x.frames; ++frame) {
            engine.step();
            const StepStats& s = engine.lastStep();
            if (frame < x.warmupFrames) continue;
            double sum = 0.0;
            for (std::size_t p = 0; p < s.passes.size() && p < samples.size(); ++p) {
                samples[p].push_back(s.passes[p].gpuMilliseconds);
                sum += s.passes[p].gpuMilliseconds;
            }
            total.push_back(sum);
            wall.push_back(s.wallMilliseconds);
        }
        for (auto& s : samples) r.passMs.push_back(summarize(s));
        r.gpuMs = summarize(total);
        r.wallMs = summarize(wall);
        r.frames = x.frames;
        const StepStats& last = engine.lastStep();
        if (last.collisions) r.set("candidate_pairs_last_substep", last.collision.candidatePairs);
        if (last.nonFinite.found)
            r.failure = "diverged: non-finite state at frame " + std::to_string(last.nonFinite.frame) +
                        ", node " + std::to_string(last.nonFinite.node);
    } catch (const Error& e) {
        r.failure = e.what();
        return r;
    }
    double detection = 0.0, features = 0.0;
    for (std::size_t p = 0; p < r.passNames.size(); ++p) {
        for (PassId id : {PassId::BBUpdate, PassId::BBCollision, PassId::BvhBuild, PassId::BvhRefit,
                          PassId::BvhTraverse, PassId::TriTri})
            if (r.passNames[p] == passes::passName(id)) detection += r.passMs[p].median;
        if (r.passNames[p] == passes::passName(PassId::FeaturePairs)) features += r.passMs[p].median;
    }
    r.set("engine_step", 1);
    r.set("gpu_ms_per_substep", r.gpuMs.median / r.substeps);
    r.set("detection_ms_per_substep", detection / r.substeps);
    r.set("feature_pairs_ms_per_substep", features / r.substeps);
    r.set("dynamics_ms_per_substep", (r.gpuMs.median - detection - features) / r.substeps);
    r.time = r.gpuMs.median / r.substeps;
    return r;
}

/// |a \ b| and |b \ a| of two sorted pair lists.
std::pair<std::size_t, std::size_t> difference(const Pairs& a, const Pairs& b) {
    std::size_t onlyA = 0, onlyB = 0, i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && a[i] < b[j]))
            ++onlyA, ++i;
        else if (i == a.size() || b[j] < a[i])
            ++onlyB, ++j;
        else
            ++i, ++j;
    }
    return {onlyA, onlyB};
}

/// Vertex-face and edge-edge pairs the candidate face pairs stand for, when each vertex and edge
/// is tested only by the face that owns it (the owned-feature bits of GpuFaceInfo, the
/// Representative-Triangle idea) and when every face tests all of its features (15 per pair).
struct FeaturePairs {
    double vertexFace = 0, edgeEdge = 0;
};

FeaturePairs featurePairsWithOwnership(const model::FlatModel& model, const Pairs& candidates) {
    const std::vector<std::uint32_t> owned = model::ownedFeatures(model.faceIndices);
    const std::uint32_t vertices = GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2;
    const std::uint32_t edges = GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20;
    FeaturePairs f;
    for (const auto& [a, b] : candidates) {
        f.vertexFace += std::popcount(owned[a] & vertices) + std::popcount(owned[b] & vertices);
        f.edgeEdge += double(std::popcount(owned[a] & edges)) * std::popcount(owned[b] & edges);
    }
    return f;
}

/// Everything measured on one scene (one row of the summary tables).
struct SceneResult {
    SceneInput input;
    std::vector<std::size_t> runs;   ///< indices into out.runs, detection runs
    std::vector<std::size_t> engine; ///< indices into out.runs, engine runs
    double candidates = std::nan("");
    bool candidatesEqual = true;
    bool featuresEqual = true; ///< the GPU's feature pairs equal the CPU count in every run
    bool cpuChecked = false;
    FeaturePairs features;
};

struct Context {
    const Experiment& x;
    ExperimentResult& out;
    const Progress& progress;
    std::vector<bool> bvhConfig;                  ///< per config
    std::vector<CollisionSettings> settings;      ///< per config, on the generated cloths
    std::map<std::string, std::uint32_t> stopped; ///< config -> faces it stopped after (slow)
    std::set<std::string> overLimit;              ///< configs skipped by octree_max_faces
};

bool runsOn(const Context& ctx, std::size_t config, const SceneInput& in) {
    const ConfigEntry& c = ctx.x.configs[config];
    if (!in.generated) {
        const auto& only = ctx.x.bvh.sceneConfigs;
        return only.empty() || std::find(only.begin(), only.end(), c.name) != only.end();
    }
    // The seed-table sizes run every configuration (slow ones timed once): the table is the point.
    if (ctx.bvhConfig[config] || in.inTable) return true;
    return !ctx.stopped.contains(c.name) &&
           (ctx.x.bvh.octreeMaxFaces == 0 || in.faces <= ctx.x.bvh.octreeMaxFaces);
}

SceneResult measureScene(Context& ctx, const SceneInput& in) {
    const Experiment& x = ctx.x;
    SceneResult result;
    result.input = in;
    std::optional<Pairs> reference;
    std::string referenceName;
    std::optional<model::FlatModel> model;
    // CPU brute force first when the scene is small enough: then every configuration is compared
    // with an answer that is not one of them.
    {
        const Scene scene = sceneFor(x, in, x.configs.front());
        model = model::flatten(scene);
        if (in.faces <= x.bvh.cpuCheckMaxFaces) {
            ctx.progress(in.name + " / CPU brute force (candidates)");
            std::vector<std::uint32_t> faceObject;
            for (std::uint32_t o = 0; o < model->objects.size(); ++o)
                faceObject.insert(faceObject.end(), model->objects[o].faceCount, o);
            std::vector<glm::vec3> positions(model->positions.begin(), model->positions.end());
            reference = cpu::twinCandidates(
                model->faceIndices, faceObject, positions, scene.collision.thickness,
                {scene.effects.has(Effect::Collisions), scene.effects.has(Effect::SelfCollisions)});
            referenceName = "the CPU brute force";
            result.cpuChecked = true;
        }
    }
    for (std::size_t c = 0; c < x.configs.size(); ++c) {
        const ConfigEntry& config = x.configs[c];
        if (!runsOn(ctx, c, in)) {
            if (in.generated && x.bvh.octreeMaxFaces && in.faces > x.bvh.octreeMaxFaces)
                ctx.overLimit.insert(config.name);
            continue;
        }
        ctx.progress(in.name + " / " + config.name);
        const Scene scene = sceneFor(x, in, config);
        Detection d = measureDetection(x, scene, in, config, x.bvh.slowRunSeconds);
        RunResult& r = d.run;
        r.set("generated", in.generated ? 1 : 0);
        if (in.generated) r.set("fold_layers", in.layers);
        r.set("in_seed_table", in.inTable ? 1 : 0);
        r.set("in_scaling", in.inScaling ? 1 : 0);
        if (d.slow) {
            r.set("measured_once_slow", 1);
            if (in.generated) ctx.stopped[config.name] = in.faces;
            ctx.out.notes.push_back(
                config.name + ": its first detection on " + in.name + " took " + ms(d.firstSeconds) +
                " s (over slow_run_seconds = " + std::to_string(x.bvh.slowRunSeconds) +
                "): timed once there" + (in.generated ? " and not run on larger cloths." : "."));
        }
        if (r.failure.empty()) {
            if (!reference) {
                reference = d.candidates;
                referenceName = "configuration \"" + config.name + "\"";
            }
            const auto [missing, extra] = difference(*reference, d.candidates);
            r.set("candidates_missing", double(missing));
            r.set("candidates_extra", double(extra));
            r.error = double(missing + extra);
            if (missing + extra) {
                r.failure = "candidates differ from " + referenceName + ": " + std::to_string(missing) +
                            " missing, " + std::to_string(extra) + " extra";
                result.candidatesEqual = false;
            }
            result.candidates = double(reference->size());
        }
        result.runs.push_back(ctx.out.runs.size());
        ctx.out.runs.push_back(std::move(r));
    }
    if (reference) {
        // The GPU's Representative-Triangle expansion (vf_pairs_gpu, ee_pairs_gpu) must give the
        // CPU's counts with ownership; a difference fails the run like a candidate difference.
        result.features = featurePairsWithOwnership(*model, *reference);
        result.candidates = double(reference->size());
        for (std::size_t i : result.runs) {
            RunResult& r = ctx.out.runs[i];
            if (r.failure.empty() && (r.metric("vf_pairs_gpu") != result.features.vertexFace ||
                                      r.metric("ee_pairs_gpu") != result.features.edgeEdge)) {
                r.failure = "feature pairs differ from the CPU count with ownership: vertex-face " +
                            grouped(std::uint64_t(r.metric("vf_pairs_gpu"))) + " vs " +
                            grouped(std::uint64_t(result.features.vertexFace)) + ", edge-edge " +
                            grouped(std::uint64_t(r.metric("ee_pairs_gpu"))) + " vs " +
                            grouped(std::uint64_t(result.features.edgeEdge));
                result.featuresEqual = false;
            }
            r.set("reference_candidate_pairs", result.candidates);
            r.set("cpu_checked", result.cpuChecked ? 1 : 0);
            r.set("feature_pairs_without_ownership", kFeaturePairsPerFacePair * result.candidates);
            r.set("vf_pairs_with_ownership", result.features.vertexFace);
            r.set("ee_pairs_with_ownership", result.features.edgeEdge);
            r.set("feature_pairs_with_ownership", result.features.vertexFace + result.features.edgeEdge);
        }
    }
    // Engine steps (dynamics + self-collisions) of the generated cloths.
    if (in.generated)
        for (std::size_t c = 0; c < x.configs.size(); ++c) {
            const ConfigEntry& config = x.configs[c];
            const auto& named = x.bvh.engineConfigs;
            const bool wanted = named.empty()
                                    ? ctx.bvhConfig[c]
                                    : std::find(named.begin(), named.end(), config.name) != named.end();
            if (!wanted || !runsOn(ctx, c, in)) continue;
            ctx.progress(in.name + " / " + config.name + " (engine step)");
            RunResult r = measureEngine(x, sceneFor(x, in, config), in, config);
            r.set("generated", 1);
            r.set("in_seed_table", in.inTable ? 1 : 0);
            r.set("in_scaling", in.inScaling ? 1 : 0);
            result.engine.push_back(ctx.out.runs.size());
            ctx.out.runs.push_back(std::move(r));
        }
    return result;
}

/// The detection (or engine) run of `s` under `config`, failed or not; null when it did not run.
const RunResult* runOf(const ExperimentResult& out, const SceneResult& s, const std::string& config,
                       bool engine) {
    for (std::size_t i : engine ? s.engine : s.runs) {
        const RunResult& r = out.runs[i];
        if (r.config == (engine ? config + " (engine step)" : config)) return &r;
    }
    return nullptr;
}

std::string cell(const ExperimentResult& out, const SceneResult& s, const std::string& config,
                 const char* key, bool engine = false) {
    const RunResult* r = runOf(out, s, config, engine);
    if (!r) return "not run";
    if (!r->failure.empty()) return "failed";
    return ms(r->metric(key, std::nan("")));
}

/// log-log slope of metric `key` against faces over the scaling cloths' runs of `config`.
double slopeOf(const ExperimentResult& out, const std::vector<SceneResult>& scenes, const std::string& config,
               const char* key, bool engine, std::uint32_t& lo, std::uint32_t& hi, int& points) {
    std::vector<RunResult> runs;
    lo = UINT32_MAX, hi = 0, points = 0;
    for (const SceneResult& s : scenes) {
        if (!s.input.inScaling) continue;
        const RunResult* r = runOf(out, s, config, engine);
        if (!r || !r->failure.empty()) continue;
        RunResult p;
        p.faces = r->faces;
        p.time = r->metric(key, std::nan(""));
        runs.push_back(p);
        lo = std::min(lo, r->faces), hi = std::max(hi, r->faces), ++points;
    }
    return logLogSlope(runs);
}

void summarise(Context& ctx, const std::vector<SceneResult>& scenes) {
    const Experiment& x = ctx.x;
    ExperimentResult& out = ctx.out;
    std::vector<std::string> bvhNames, octreeNames;
    for (std::size_t c = 0; c < x.configs.size(); ++c)
        (ctx.bvhConfig[c] ? bvhNames : octreeNames).push_back(x.configs[c].name);
    // The BVH column of the seed tables: the first bvh config that rebuilds every substep (every
    // detection then builds, refits and traverses), else the first bvh config.
    std::string tableBvh;
    for (std::size_t c = 0; c < x.configs.size() && tableBvh.empty(); ++c)
        if (ctx.bvhConfig[c] && ctx.settings[c].bvh.rebuild == BvhRebuild::EverySubstep)
            tableBvh = x.configs[c].name;
    if (tableBvh.empty() && !bvhNames.empty()) tableBvh = bvhNames.front();

    bool allEqual = true;
    for (const SceneResult& s : scenes) allEqual = allEqual && s.candidatesEqual;
    out.summary.push_back({"candidates_equal_in_every_configuration", allEqual ? 1.0 : 0.0});

    // 1. The seed's Tables 1-3, side by side with this run.
    const auto seedRow = [](std::uint32_t faces) -> const SeedTableRow* {
        for (const SeedTableRow& row : seedTables())
            if (row.triangles == faces) return &row;
        return nullptr;
    };
    {
        SummaryTable t;
        t.title =
            "Seed Tables 1-3 layout: folded cloth, ms per detection (median), seed GPU numbers as printed";
        t.header = {"triangles",         "build: " + (tableBvh.empty() ? std::string("bvh") : tableBvh),
                    "build: seed GPU",   "refit",
                    "refit: seed GPU",   "traverse",
                    "traverse: seed GPU"};
        for (const std::string& o : octreeNames) t.header.push_back(o + ": BBUpdate / BBCollision");
        t.header.insert(t.header.end(), {"candidates", "equal in all configs"});
        for (const SceneResult& s : scenes) {
            if (!s.input.inTable) continue;
            const SeedTableRow* seed = seedRow(s.input.faces);
            std::vector<std::string> row{grouped(s.input.faces)};
            for (const auto& [key, column] :
                 {std::pair{"build_ms", 0}, {"refit_ms", 1}, {"traverse_ms", 2}}) {
                row.push_back(tableBvh.empty() ? "no bvh config" : cell(out, s, tableBvh, key));
                row.push_back(!seed         ? "-"
                              : column == 0 ? seed->build[0]
                              : column == 1 ? seed->refit[0]
                                            : seed->traverse[0]);
            }
            for (const std::string& o : octreeNames)
                row.push_back(cell(out, s, o, "bbupdate_ms") + " / " + cell(out, s, o, "bbcollision_ms"));
            row.push_back(std::isnan(s.candidates) ? "-" : grouped(static_cast<std::uint64_t>(s.candidates)));
            row.push_back(s.candidatesEqual ? (s.cpuChecked ? "yes (and = CPU brute force)" : "yes") : "NO");
            t.rows.push_back(std::move(row));
        }
        if (!t.rows.empty()) out.tables.push_back(std::move(t));
        SummaryTable printed;
        printed.title =
            "The seed's Tables 1-3 exactly as printed (OCR of seeds/001; garbled cells quoted, not "
            "interpreted)";
        printed.header = {"# of triangles",      "Table 1 build GPU", "Table 1 build CPU",
                          "Table 2 refit GPU",   "Table 2 refit CPU", "Table 3 traverse GPU",
                          "Table 3 traverse CPU"};
        for (const SeedTableRow& row : seedTables())
            printed.rows.push_back({grouped(row.triangles), row.build[0], row.build[1], row.refit[0],
                                    row.refit[1], row.traverse[0], row.traverse[1]});
        if (!x.bvh.tableFaces.empty()) out.tables.push_back(std::move(printed));
    }

    // 2. Scaling: detection and engine step per size, then the exponents.
    {
        SummaryTable t;
        t.title = "Scaling: folded cloth, GPU ms per detection (broad phase + TriTri) and per engine substep";
        t.header = {"faces", "candidates"};
        for (const auto& c : x.configs) t.header.push_back(c.name + ": detection (broad phase)");
        std::vector<std::string> engineNames;
        for (const SceneResult& s : scenes)
            for (std::size_t i : s.engine) {
                const std::string& n = out.runs[i].config;
                if (std::find(engineNames.begin(), engineNames.end(), n) == engineNames.end())
                    engineNames.push_back(n);
            }
        for (const std::string& n : engineNames) t.header.push_back(n + ": ms per substep");
        for (const SceneResult& s : scenes) {
            if (!s.input.inScaling) continue;
            std::vector<std::string> row{grouped(s.input.faces), std::isnan(s.candidates)
                                                                     ? "-"
                                                                     : grouped(std::uint64_t(s.candidates))};
            for (const auto& c : x.configs)
                row.push_back(cell(out, s, c.name, "detection_ms") + " (" +
                              cell(out, s, c.name, "broad_phase_ms") + ")");
            for (const std::string& n : engineNames) {
                std::string value = "not run";
                for (std::size_t i : s.engine)
                    if (out.runs[i].config == n)
                        value = out.runs[i].failure.empty() ? ms(out.runs[i].time) : "failed";
                row.push_back(value);
            }
            t.rows.push_back(std::move(row));
        }
        if (!t.rows.empty()) out.tables.push_back(std::move(t));

        SummaryTable slopes;
        slopes.title =
            "Cost exponent: least-squares slope of log(ms) against log(faces) over the scaling cloths";
        slopes.header = {"configuration", "what", "exponent", "fitted over faces", "points"};
        const auto addSlope = [&](const std::string& config, const char* key, bool engine,
                                  const std::string& what, const std::string& metricName) {
            std::uint32_t lo = 0, hi = 0;
            int points = 0;
            const double slope = slopeOf(out, scenes, config, key, engine, lo, hi, points);
            if (points == 0) return;
            slopes.rows.push_back(
                {config, what, ms(slope), grouped(lo) + " - " + grouped(hi), std::to_string(points)});
            out.summary.push_back({metricName + "/" + config, slope});
        };
        for (std::size_t i = 0; i < x.configs.size(); ++i) {
            const ConfigEntry& c = x.configs[i];
            addSlope(c.name, "detection_ms", false, "detection (broad phase + TriTri) per substep",
                     "slope_detection");
            addSlope(c.name, "broad_phase_ms", false, "broad phase per substep", "slope_broad_phase");
            if (ctx.bvhConfig[i])
                addSlope(c.name, "bvh_node_visits", false,
                         "BVH traversal node visits (a work count: independent of timing noise)",
                         "slope_bvh_node_visits");
            addSlope(c.name, "gpu_ms_per_substep", true,
                     "engine step per substep (dynamics + self-collisions)", "slope_engine_substep");
            addSlope(c.name, "detection_ms_per_substep", true,
                     "engine step: its detection passes per substep", "slope_engine_detection_substep");
        }
        if (!slopes.rows.empty()) out.tables.push_back(std::move(slopes));
    }

    // 3. Suite scenes (cloth_ball92): detection time of every configuration against the BVH's.
    for (const SceneResult& s : scenes) {
        if (s.input.generated) continue;
        SummaryTable t;
        t.title = s.input.name + " (" + grouped(s.input.faces) + " faces): one run, ratios within it";
        t.header = {"configuration",
                    "broad phase ms",
                    "detection ms",
                    "candidates",
                    "detection / " + (bvhNames.empty() ? std::string("bvh") : bvhNames.front()),
                    "broad phase / " + (bvhNames.empty() ? std::string("bvh") : bvhNames.front())};
        const RunResult* base = bvhNames.empty() ? nullptr : runOf(out, s, bvhNames.front(), false);
        if (base && !base->failure.empty()) base = nullptr;
        for (std::size_t i : s.runs) {
            const RunResult& r = out.runs[i];
            if (!r.failure.empty()) {
                t.rows.push_back({r.config, "failed: " + r.failure, "-", "-", "-", "-"});
                continue;
            }
            const double detection = r.metric("detection_ms"), broad = r.metric("broad_phase_ms");
            std::string ratio = "-", broadRatio = "-";
            if (base) {
                ratio = ms(detection / base->metric("detection_ms"));
                broadRatio = ms(broad / base->metric("broad_phase_ms"));
                out.summary.push_back({"ratio_detection/" + s.input.name + "/" + r.config,
                                       detection / base->metric("detection_ms")});
                out.summary.push_back({"ratio_broad_phase/" + s.input.name + "/" + r.config,
                                       broad / base->metric("broad_phase_ms")});
            }
            t.rows.push_back({r.config, ms(broad), ms(detection),
                              grouped(std::uint64_t(r.metric("candidate_pairs"))), ratio, broadRatio});
        }
        out.tables.push_back(std::move(t));
    }

    // 4. Memory: the broad phase's own bytes per face.
    {
        SummaryTable t;
        t.title = "Memory: bytes of the broad phase's own buffers per face (target for the BVH: <= " +
                  ms(kBytesPerFaceTarget) + ")";
        t.header = {"configuration", "largest bytes per face", "at faces", "within target"};
        for (std::size_t c = 0; c < x.configs.size(); ++c) {
            double largest = -1;
            std::uint32_t at = 0;
            for (const SceneResult& s : scenes)
                for (std::size_t i : s.runs) {
                    const RunResult& r = out.runs[i];
                    if (r.config != x.configs[c].name || r.metrics.empty()) continue;
                    const double b = r.metric("broad_phase_bytes_per_face", -1);
                    if (b > largest) largest = b, at = r.faces;
                }
            if (largest < 0) continue;
            const bool ok = largest <= kBytesPerFaceTarget;
            t.rows.push_back(
                {x.configs[c].name, ms(largest), grouped(at), ctx.bvhConfig[c] ? (ok ? "yes" : "NO") : "-"});
            out.summary.push_back({"max_bytes_per_face/" + x.configs[c].name, largest});
        }
        out.summary.push_back({"bytes_per_face_target", kBytesPerFaceTarget});
        if (!t.rows.empty()) out.tables.push_back(std::move(t));
    }

    // 5. Feature pairs with and without ownership (R-Triangles).
    {
        const std::string timed = bvhNames.empty() ? x.configs.front().name : bvhNames.front();
        SummaryTable t;
        t.title =
            "Feature pairs behind the candidate face pairs: without ownership (15 per pair) and with the "
            "owned-feature bits (Representative Triangles), GPU counts checked against the CPU's";
        t.header = {"scene",
                    "candidates",
                    "without ownership",
                    "with ownership: vertex-face",
                    "edge-edge",
                    "total",
                    "with / without",
                    "GPU = CPU in every run",
                    "FeaturePairs ms (" + timed + ")"};
        for (const SceneResult& s : scenes) {
            if (std::isnan(s.candidates)) continue;
            const double without = kFeaturePairsPerFacePair * s.candidates;
            const double with = s.features.vertexFace + s.features.edgeEdge;
            t.rows.push_back({s.input.name, grouped(std::uint64_t(s.candidates)),
                              grouped(std::uint64_t(without)), grouped(std::uint64_t(s.features.vertexFace)),
                              grouped(std::uint64_t(s.features.edgeEdge)), grouped(std::uint64_t(with)),
                              without > 0 ? ms(with / without) : "-", s.featuresEqual ? "yes" : "NO",
                              cell(out, s, timed, "feature_pairs_ms")});
        }
        if (!t.rows.empty()) out.tables.push_back(std::move(t));
    }
    bool featuresEqual = true;
    for (const SceneResult& s : scenes) featuresEqual = featuresEqual && s.featuresEqual;
    out.summary.push_back({"feature_pairs_gpu_equal_cpu_in_every_run", featuresEqual ? 1.0 : 0.0});
}

} // namespace

const std::array<SeedTableRow, 3>& seedTables() {
    // seeds/001_0c579410544660af.txt, Tables 1-3, cell for cell.
    static const std::array<SeedTableRow, 3> rows = {{
        {2244, {"23.94 ms", "571 ms"}, {"0.16 vs", "0.31 us"}, {"1.19 ms", "10.28 ms"}},
        {27030, {"59.12 ms", "45.18 ms"}, {"0.18 s", "1.28 us"}, {"12.52 ms", "162.92 ms"}},
        {35992, {"012 s", "0.98 s"}, {"0.35 vus", "481 ps"}, {"041 s", "8.65 s"}},
    }};
    return rows;
}

std::size_t bvhRunCount(const Experiment& x) {
    std::set<std::uint32_t> sizes(x.bvh.tableFaces.begin(), x.bvh.tableFaces.end());
    sizes.insert(x.bvh.scalingFaces.begin(), x.bvh.scalingFaces.end());
    const std::size_t engine = x.bvh.engineConfigs.empty() ? 1 : x.bvh.engineConfigs.size();
    return sizes.size() * (x.configs.size() + engine + 1) + x.scenes.size() * (x.configs.size() + 1);
}

void runBvhExperiment(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "GPU ms per detection (engine rows: per substep)";
    out.errorLabel = "candidate pairs differing from the reference";
    out.errorIsCount = true;
    Context ctx{x, out, progress, {}, {}, {}, {}};
    for (const ConfigEntry& c : x.configs) {
        ctx.settings.push_back(configSettings(x, c));
        ctx.bvhConfig.push_back(ctx.settings.back().broadPhase == BroadPhase::Bvh);
    }

    const Scene base =
        parseScene(clothDocument(x).dump(), {}, "bvh experiment \"" + x.name + "\" cloth scene");
    std::set<std::uint32_t> sizes(x.bvh.tableFaces.begin(), x.bvh.tableFaces.end());
    sizes.insert(x.bvh.scalingFaces.begin(), x.bvh.scalingFaces.end());
    std::vector<SceneResult> scenes;
    for (std::uint32_t faces : sizes) {
        SceneInput in;
        in.faces = faces;
        in.generated = true;
        in.name = "folded cloth " + grouped(faces) + " faces";
        in.inTable =
            std::find(x.bvh.tableFaces.begin(), x.bvh.tableFaces.end(), faces) != x.bvh.tableFaces.end();
        in.inScaling = std::find(x.bvh.scalingFaces.begin(), x.bvh.scalingFaces.end(), faces) !=
                       x.bvh.scalingFaces.end();
        const FoldedClothSpec spec{
            .faces = faces, .thickness = base.collision.thickness, .layers = x.bvh.foldLayers};
        in.cloth = foldedCloth(spec);
        in.layers = foldedClothLayers(spec);
        scenes.push_back(measureScene(ctx, in));
    }
    for (const SceneEntry& s : x.scenes) {
        SceneInput in;
        in.name = s.name;
        in.entry = &s;
        in.faces = static_cast<std::uint32_t>(model::flatten(sceneFor(x, in, x.configs.front())).faceCount());
        scenes.push_back(measureScene(ctx, in));
    }
    summarise(ctx, scenes);

    FoldedClothSpec spec;
    spec.thickness = base.collision.thickness;
    std::vector<std::string> notes;
    if (!sizes.empty())
        notes.push_back(
            "Folded cloth (benchkit/folded_cloth.hpp): a grid of square cells of " +
            metres(spec.cellFactor * spec.thickness) +
            " m with exactly the stated number of triangles (the surplus of the last row dropped), folded "
            "like "
            "an accordion into " +
            std::to_string(x.bvh.foldLayers) +
            " layers (fewer where a panel would be shorter than two cells: run metric fold_layers) " +
            metres(spec.spacingFactor * spec.thickness) + " m apart (" + metres(spec.spacingFactor) +
            " x the contact thickness " + metres(spec.thickness) +
            " m) joined by half circles, and crumpled by a height field of amplitude " +
            metres(spec.amplitudeFactor * spec.cellFactor * spec.thickness) +
            " m common to all layers. Effects gravity, springs (edges, at rest) and self_collisions; one "
            "object, so every candidate is a self-collision pair.");
    notes.push_back(
        "Detection rows: one substep's collision detection (CollisionDetection::detect: the broad "
        "phase's passes, TriTri, then FeaturePairs) on the scene's positions, " +
        std::to_string(x.warmupFrames) + " warm-up and " + std::to_string(x.frames) +
        " timed repetitions, each bracketed by GL_TIMESTAMP queries per pass; medians. A bvh config "
        "that rebuilds every substep builds, refits and traverses in every repetition. Engine rows: "
        "whole Engine::step() frames (dynamics + self-collision detection + contact response), ms "
        "per substep.");
    notes.push_back(
        "Candidates: every configuration of a scene must report the same candidate pairs as the "
        "reference (the CPU brute force cpu::twinCandidates up to " +
        grouped(x.bvh.cpuCheckMaxFaces) +
        " faces, else the first configuration that ran); a difference fails the run (error column "
        "= pairs missing + extra).");
    if (!x.bvh.tableFaces.empty())
        notes.push_back(
            "Seed numbers: Tables 1-3 of seeds/001 (Kim 2024, CUDA) are quoted exactly as the OCR "
            "printed them; several cells are garbled (\"012 s\", \"0.16 vs\", \"0.35 vus\", "
            "\"481 ps\", \"041 s\") and are not interpreted. The seed's cloth scenes are not "
            "available: its sizes are matched, not its meshes; what its build and refit include "
            "is not stated in the tables.");
    out.notes.insert(out.notes.begin(), notes.begin(), notes.end());
    if (x.bvh.octreeMaxFaces) {
        std::string skipped;
        for (const std::string& n : ctx.overLimit) skipped += (skipped.empty() ? "" : ", ") + n;
        out.notes.push_back("Cutoff: octree configurations run on generated cloths of at most " +
                            grouped(x.bvh.octreeMaxFaces) + " faces (octree_max_faces)" +
                            (skipped.empty() ? "." : "; not run above it: " + skipped + "."));
    }
    out.notes.push_back(
        "Feature pairs: without ownership every candidate face pair stands for 15 (3 + 3 vertex-face, "
        "9 edge-edge); with ownership (Representative Triangles: each vertex and edge tested only by "
        "the face that owns it, GpuFaceInfo's owned bits) counted on the CPU from the reference "
        "candidates, and by the GPU's FeaturePairs stage in every detection run (vf_pairs_gpu, "
        "ee_pairs_gpu): a difference fails the run. FeaturePairs is timed on its own, not in detection_ms.");
    for (const RunResult& r : out.runs)
        if (!r.failure.empty() && r.failure.find("work in progress") != std::string::npos) {
            out.notes.push_back("The bvh broad phase is not in this build (\"" + r.failure +
                                "\"): its runs are failed rows.");
            break;
        }
}

} // namespace glcollide::benchkit
