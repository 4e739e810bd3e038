#include "benchkit/experiments.hpp"

#include "benchkit/bvh_experiment.hpp"
#include "benchkit/ccd_experiment.hpp"
#include "benchkit/oscillator.hpp"
#include "benchkit/paper_fused_tri_tri.hpp"
#include "benchkit/response_experiment.hpp"

#include "core/gpu_layout.hpp"
#include "cpu/oracle/ground_truth.hpp"
#include "cpu/oracle/tri_tri_cases.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"
#include "passes/tri_tri_query_pass.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>

namespace glcollide::benchkit {

using json = nlohmann::json;

Scene buildScene(const SceneEntry& entry, const ConfigEntry& config) {
    json document = json::parse(entry.sceneJson);
    document.merge_patch(json::parse(config.patchJson));
    Scene scene =
        parseScene(document.dump(), entry.baseDir, entry.source + " (config \"" + config.name + "\")");
    if (scene.name.empty()) scene.name = entry.name;
    return scene;
}

void applySubstepFactor(Scene& scene, int factor) {
    if (factor == 1) return;
    const int base = scene.time.substeps != 0 ? scene.time.substeps
                                              : Engine(scene, {.gpuTiming = false}).substepInfo().substeps;
    scene.time.substeps = base * factor;
}

RunResult measureRun(Engine& engine, const Experiment& experiment, const FrameHook& hook) {
    RunResult r;
    r.nodes = engine.nodeCount();
    r.springs = engine.springCount();
    r.faces = engine.faceCount();
    r.substeps = engine.substepInfo().substeps;
    r.frames = experiment.frames;
    r.passNames = engine.pipeline();
    std::vector<std::vector<double>> passSamples(r.passNames.size());
    std::vector<double> gpu, wall;
    double maxIntersecting = 0, maxContacts = 0, candidates = 0, growths = 0;
    const int total = experiment.warmupFrames + experiment.frames;
    for (int frame = 1; frame <= total; ++frame) {
        engine.step();
        const StepStats& s = engine.lastStep();
        if (s.collisions) {
            maxIntersecting = std::max(maxIntersecting, double(s.collision.maxIntersectingPairs));
            maxContacts = std::max(maxContacts, double(s.collision.contacts));
            candidates = s.collision.candidatePairs;
            growths += s.collision.listGrowths;
        }
        if (frame > experiment.warmupFrames) {
            double sum = 0.0;
            for (std::size_t p = 0; p < s.passes.size(); ++p) {
                passSamples[p].push_back(s.passes[p].gpuMilliseconds);
                sum += s.passes[p].gpuMilliseconds;
            }
            gpu.push_back(sum);
            wall.push_back(s.wallMilliseconds);
        }
        if (hook) hook(engine, frame);
    }
    for (auto& samples : passSamples) r.passMs.push_back(summarize(samples));
    r.gpuMs = summarize(gpu);
    r.wallMs = summarize(wall);
    r.set("substeps_per_frame", r.substeps);
    if (engine.lastStep().collisions) {
        r.set("candidate_pairs_last_substep", candidates);
        r.set("max_intersecting_pairs", maxIntersecting);
        r.set("max_contacts", maxContacts);
        r.set("list_growths", growths);
    }
    const NonFiniteReport& bad = engine.lastStep().nonFinite; // detected on the device, no readback
    if (bad.found)
        r.failure = "diverged: non-finite state at frame " + std::to_string(bad.frame) + ", object " +
                    std::to_string(bad.object) + ", node " + std::to_string(bad.node);
    return r;
}

namespace {

using Pairs = std::vector<std::array<std::uint32_t, 2>>;

double passMedian(const RunResult& r, std::initializer_list<const char*> names) {
    double sum = 0.0;
    for (std::size_t p = 0; p < r.passNames.size(); ++p)
        for (const char* n : names)
            if (r.passNames[p] == n) sum += r.passMs[p].median;
    return sum;
}

std::size_t countMissing(const Pairs& wanted, const Pairs& have) {
    Pairs missing;
    std::set_difference(wanted.begin(), wanted.end(), have.begin(), have.end(), std::back_inserter(missing));
    return missing.size();
}

/// The faces' objects and the pair rules of the scene's collision effects.
struct FaceData {
    model::FlatModel model;
    std::vector<std::uint32_t> faceObject, nodeObject;
    std::vector<bool> closed;
    cpu::PairRules rules;
};

FaceData faceData(const Scene& scene) {
    FaceData d;
    d.model = model::flatten(scene);
    d.nodeObject = model::nodeObjects(d.model);
    for (std::uint32_t o = 0; o < d.model.objects.size(); ++o) {
        const model::ObjectRange& r = d.model.objects[o];
        d.faceObject.insert(d.faceObject.end(), r.faceCount, o);
        d.closed.push_back(model::isClosedSurface(d.model.faceIndices, r.firstFace, r.faceCount));
    }
    d.rules.betweenObjects = scene.effects.has(Effect::Collisions);
    d.rules.selfCollisions = scene.effects.has(Effect::SelfCollisions);
    return d;
}

/// Runs detection on the final state and compares candidates and intersections with the exact
/// set of intersecting face pairs over all valid pairs.
void compareWithOracle(Engine& engine, const FaceData& d, RunResult& r) {
    engine.detectCollisions();
    Pairs found = engine.readIntersectingPairs();
    Pairs candidates = engine.readCandidatePairs();
    std::sort(found.begin(), found.end());
    std::sort(candidates.begin(), candidates.end());
    std::vector<glm::vec3> positions;
    for (const glm::dvec3& p : engine.readPositions()) positions.emplace_back(p);
    const Pairs truth = cpu::exactIntersectingPairs(d.model.faceIndices, d.faceObject, positions, d.rules);
    r.set("exact_intersecting_pairs", double(truth.size()));
    r.set("candidate_pairs", double(candidates.size()));
    r.set("reported_intersecting_pairs", double(found.size()));
    r.set("candidates_missing_intersections", double(countMissing(truth, candidates)));
    r.set("false_negatives", double(countMissing(truth, found)));
    r.set("false_positives", double(countMissing(found, truth)));
}

/// Called once after the measured frames, while the engine still holds the final state.
using AfterRun = std::function<void(Engine&, const Scene&, RunResult&)>;

/// Called once before the first frame, with the engine in its initial state.
using BeforeRun = std::function<void(Engine&)>;

/// One scene under one configuration: built, `before`, measured, then `after` (ground truth on
/// the state).
RunResult runScene(const Experiment& x, const SceneEntry& s, const ConfigEntry& c, const FrameHook& hook,
                   const AfterRun& after = nullptr, const BeforeRun& before = nullptr) {
    Scene scene = buildScene(s, c);
    applySubstepFactor(scene, c.substepFactor);
    Engine engine(scene);
    if (before) before(engine);
    RunResult r = measureRun(engine, x, hook);
    r.scene = s.name;
    r.config = c.name;
    if (after && r.failure.empty()) after(engine, scene, r);
    return r;
}

// --- experiments -------------------------------------------------------------------------------

void scaling(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "GPU ms per substep";
    out.errorLabel = "";
    for (const ConfigEntry& c : x.configs)
        for (const SceneEntry& s : x.scenes) {
            progress(s.name + " / " + c.name);
            RunResult r = runScene(x, s, c, nullptr);
            r.time = r.gpuMs.median / r.substeps;
            out.runs.push_back(std::move(r));
        }
}

/// The paper's fused TriTri (masked or all pairs, benchkit/paper_fused_tri_tri.hpp) on the engine's
/// final state, as a run of its own next to the engine's pipeline: its time is the GPU time of the
/// whole scheme per substep (BBUpdate, mask, fused TriTri), its error the exactly intersecting
/// pairs missing from its candidates, like the broad phases'.
RunResult paperFusedRun(const Experiment& x, Engine& engine, const Scene& scene, const FaceData& d,
                        const RunResult& engineRun) {
    const bool masked = scene.collision.broadPhase == BroadPhase::Masked;
    PaperFusedTriTri paper(d.model, scene.collision, d.rules.betweenObjects, d.rules.selfCollisions, masked);
    std::vector<glm::vec3> positions;
    for (const glm::dvec3& p : engine.readPositions()) positions.emplace_back(p);
    const PaperFusedAnswer answer = paper.run(positions, x.warmupFrames, std::max(1, x.frames));
    RunResult r;
    r.scene = engineRun.scene;
    r.config = engineRun.config + " (paper: fused TriTri)";
    r.nodes = engineRun.nodes;
    r.faces = engineRun.faces;
    r.substeps = 1;
    r.frames = static_cast<int>(answer.milliseconds.size());
    r.passNames = {"fused"};
    r.passMs = {summarize(answer.milliseconds)};
    r.gpuMs = r.passMs[0];
    const Pairs truth = cpu::exactIntersectingPairs(d.model.faceIndices, d.faceObject, positions, d.rules);
    r.set("exact_intersecting_pairs", double(truth.size()));
    r.set("candidate_pairs", double(answer.candidates.size()));
    r.set("reported_intersecting_pairs", double(answer.intersections.size()));
    r.set("candidates_missing_intersections", double(countMissing(truth, answer.candidates)));
    r.set("false_negatives", double(countMissing(truth, answer.intersections)));
    r.set("false_positives", double(countMissing(answer.intersections, truth)));
    r.time = r.gpuMs.median;
    r.error = r.metric("candidates_missing_intersections");
    return r;
}

void broadOrNarrow(const Experiment& x, ExperimentResult& out, const Progress& progress, bool broad) {
    out.timeLabel = broad ? "collision detection GPU ms per substep" : "TriTri GPU ms per substep";
    out.errorLabel =
        broad ? "intersecting pairs missed by the broad phase" : "disagreements with the exact oracle";
    out.errorIsCount = true;
    bool paperRuns = false;
    for (const SceneEntry& s : x.scenes)
        for (const ConfigEntry& c : x.configs) {
            progress(s.name + " / " + c.name);
            std::optional<RunResult> paper;
            RunResult r = runScene(x, s, c, nullptr, [&](Engine& engine, const Scene& scene, RunResult& run) {
                if (!scene.effects.has(Effect::Collisions) && !scene.effects.has(Effect::SelfCollisions))
                    throw Error(s.source + " (config \"" + c.name + "\"): a " + kindName(x.kind) +
                                " experiment needs the collisions or self_collisions effect");
                const FaceData data = faceData(scene);
                compareWithOracle(engine, data, run);
                if (broad && scene.collision.broadPhase != BroadPhase::Octree) {
                    progress(s.name + " / " + c.name + " (paper: fused TriTri)");
                    paper = paperFusedRun(x, engine, scene, data, run);
                }
            });
            if (broad) {
                r.time = passMedian(r, {"BBUpdate", "BBCollision", "TriTri"}) / r.substeps;
                r.error = r.metric("candidates_missing_intersections");
            } else {
                r.time = passMedian(r, {"TriTri"}) / r.substeps;
                r.error = r.metric("false_negatives") + r.metric("false_positives");
            }
            out.runs.push_back(std::move(r));
            if (paper) {
                out.runs.push_back(std::move(*paper));
                paperRuns = true;
            }
        }
    if (broad)
        out.notes.push_back(
            "Ground truth: every valid face pair of the final state tested by the exact rational "
            "oracle (sort-and-sweep over exact float boxes first). The error is the number of "
            "exactly intersecting pairs the broad phase did not report as candidates.");
    else
        out.notes.push_back(
            "Ground truth: the exact rational oracle on every valid face pair of the final state. "
            "Disagreements = false positives + false negatives of the reported intersecting pairs.");
    if (paperRuns)
        out.notes.push_back(
            "\"(paper: fused TriTri)\": the paper's own scheme (seeds/002 Alg. 2-3) on the final "
            "state: every valid face pair tested by the fast triangle test in one kernel (masked: "
            "behind the leaf-box overlap mask), GPU ms per run of BBUpdate + mask + fused TriTri. "
            "The engine's masked and all-pairs broad phases instead append candidates and run "
            "TriTri on that list.");
}

/// A family of triangle pairs with its exact answers.
struct Family {
    std::vector<cpu::FloatTriPair> pairs;
    std::vector<std::uint8_t> exact;
};

Family makeFamily(const std::string& name) {
    Family f;
    if (name == "hard") {
        for (const cpu::NamedTriPair& p : cpu::hardTriTriCases()) f.pairs.push_back(p.pair);
    } else {
        for (cpu::TriTriSet set : cpu::kAllTriTriSets)
            if (name == cpu::toString(set))
                f.pairs = cpu::randomTriTriPairs(set, 16384, 1000u + static_cast<std::uint32_t>(set));
    }
    for (const cpu::FloatTriPair& p : f.pairs) f.exact.push_back(cpu::exactPairIntersects(p) ? 1 : 0);
    return f;
}

/// One batch of the family through the TriTri query pass: the answers once, then `frames`
/// timed dispatches on resident buffers.
RunResult runFamily(const Experiment& x, const std::string& name, const Family& f, const ConfigEntry& c,
                    TriTriPrecision precision) {
    RunResult r;
    r.scene = "pairs: " + name;
    r.config = c.name;
    r.frames = x.frames;
    r.substeps = 1;
    r.passNames = {"TriTri"};
    const passes::TriTriQueryPass pass(precision);
    const passes::TriTriQueryResult answers = pass.run(f.pairs);
    double fp = 0, fn = 0;
    for (std::size_t i = 0; i < f.exact.size(); ++i) {
        fp += answers.intersect[i] && !f.exact[i] ? 1 : 0;
        fn += !answers.intersect[i] && f.exact[i] ? 1 : 0;
    }
    const auto n = static_cast<std::uint32_t>(f.pairs.size());
    passes::TriTriQueryBatch batch = pass.upload(f.pairs);
    gl::GpuTimer timer(1);
    std::vector<double> ms;
    for (int i = 0; i < x.warmupFrames + x.frames; ++i) {
        timer.beginFrame();
        timer.begin(0);
        pass.dispatch(batch);
        timer.end(0);
        const double t = timer.resolveMilliseconds()[0];
        if (i >= x.warmupFrames) ms.push_back(t);
    }
    r.passMs = {summarize(ms)};
    r.gpuMs = r.passMs[0];
    r.set("pairs", n);
    r.set("exact_intersecting_pairs", double(std::count(f.exact.begin(), f.exact.end(), std::uint8_t{1})));
    r.set("false_positives", fp);
    r.set("false_negatives", fn);
    r.set("exact_fallbacks", double(answers.exactFallbacks));
    r.set("undecided_pairs", double(answers.undecidedPairs));
    r.set("gpu_ns_per_pair", r.gpuMs.median * 1e6 / n);
    r.time = r.gpuMs.median;
    r.error = fp + fn;
    return r;
}

void narrowPhase(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    broadOrNarrow(x, out, progress, false);
    for (const std::string& name : x.caseFamilies) {
        const Family family = makeFamily(name);
        for (const ConfigEntry& c : x.configs) {
            progress("pairs: " + name + " / " + c.name);
            const TriTriPrecision precision = buildScene(x.scenes.front(), c).collision.precision;
            out.runs.push_back(runFamily(x, name, family, c, precision));
        }
    }
    if (!x.caseFamilies.empty())
        out.notes.push_back(
            "Pair families (\"pairs: ...\"): one batch through the TriTri query pass with each "
            "configuration's precision; time is GPU ms per batch, ground truth the exact oracle.");
}

/// Node positions and energy after every frame (warm-up frames included), and before the first.
struct Trajectory {
    std::vector<std::vector<glm::dvec3>> positions;
    std::vector<double> energy;
    double initialEnergy = 0.0;
    double dt = 0.0; ///< s per frame
    int stabilityRuleSubsteps = 0;
};

FrameHook recordTrajectory(Trajectory& t) {
    return [&t](Engine& e, int) {
        t.positions.push_back(e.readPositions());
        t.energy.push_back(e.energy().total());
    };
}

BeforeRun recordStart(Trajectory& t) {
    return [&t](Engine& e) {
        t.initialEnergy = e.energy().total();
        t.dt = e.scene().time.dt;
        t.stabilityRuleSubsteps = e.substepInfo().stableSubsteps;
    };
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// What every integration run reports besides its error: the cost of one simulated second and
/// the energy drift over the run.
void addCostAndDrift(const Trajectory& t, RunResult& r) {
    r.set("dt_s", t.dt);
    r.set("gpu_ms_per_simulated_second", r.gpuMs.median / t.dt);
    r.set("wall_ms_per_simulated_second", r.wallMs.median / t.dt);
    r.set("stability_rule_substeps", t.stabilityRuleSubsteps);
    const double end = t.energy.empty() ? t.initialEnergy : t.energy.back();
    // Relative to |E(0)|; no relative drift exists for a state that starts with zero energy.
    r.set("energy_drift_relative",
          t.initialEnergy != 0.0 ? (end - t.initialEnergy) / std::abs(t.initialEnergy) : kNaN);
}

/// A body in free flight under gravity with its springs at rest: every free node moves on the
/// parabola x(t) = x0 + v0 t + g t^2 / 2 (the springs never stretch, since all free nodes share one
/// velocity), pinned nodes stay. The exact solution of the discrete system, so any error is the
/// integrator's (symplectic Euler: g h t / 2, first order in h) plus float rounding.
struct Ballistic {
    std::vector<glm::dvec3> start, velocity;
    std::vector<bool> pinned;
    glm::dvec3 gravity{0.0};
    std::vector<double> masses;

    [[nodiscard]] std::vector<glm::dvec3> positions(double t) const {
        std::vector<glm::dvec3> x;
        for (std::size_t i = 0; i < start.size(); ++i)
            x.push_back(pinned[i] ? start[i] : start[i] + velocity[i] * t + 0.5 * gravity * t * t);
        return x;
    }
    /// Kinetic + gravitational energy (springs stay at rest): constant in time.
    [[nodiscard]] double energy() const {
        double e = 0.0;
        for (std::size_t i = 0; i < start.size(); ++i)
            if (!pinned[i])
                e += 0.5 * masses[i] * glm::dot(velocity[i], velocity[i]) -
                     masses[i] * glm::dot(gravity, start[i]);
        return e;
    }
};

Ballistic ballisticOf(const Scene& scene, const std::string& source) {
    const auto fail = [&](const std::string& what) -> Ballistic {
        throw Error(source +
                    ": the ballistic reference needs effects gravity (and optionally springs) only, no "
                    "spring between a pinned and a free node, and one velocity for all free nodes: " +
                    what);
    };
    for (Effect e : scene.effects.list())
        if (e != Effect::Gravity && e != Effect::Springs)
            return fail("effect " + std::string(effectName(e)) + " is on");
    if (!scene.effects.has(Effect::Gravity)) return fail("gravity is off");
    const model::FlatModel m = model::flatten(scene);
    Ballistic b;
    b.start = m.positions;
    b.velocity = m.velocities;
    b.masses = m.masses;
    b.gravity = scene.gravity;
    for (double w : m.inverseMasses) b.pinned.push_back(w == 0.0);
    std::optional<glm::dvec3> shared;
    for (std::size_t i = 0; i < m.nodeCount(); ++i) {
        if (b.pinned[i]) continue;
        if (shared && *shared != m.velocities[i])
            return fail("node " + std::to_string(i) + " has another velocity");
        shared = m.velocities[i];
    }
    if (scene.effects.has(Effect::Springs))
        for (const model::FlatSpring& sp : m.springs)
            if (b.pinned[sp.a] != b.pinned[sp.b])
                return fail("a spring joins pinned node " + std::to_string(b.pinned[sp.a] ? sp.a : sp.b) +
                            " to a free one");
    return b;
}

/// Largest node distance from the reference over all frames, and the largest energy difference
/// relative to the reference's initial energy.
void compareTrajectories(const Trajectory& run, const Trajectory& ref, double referenceEnergy, RunResult& r) {
    double error = 0.0, energyError = 0.0;
    const std::size_t frames = std::min(run.positions.size(), ref.positions.size());
    for (std::size_t f = 0; f < frames; ++f) {
        for (std::size_t i = 0; i < run.positions[f].size(); ++i)
            error = std::max(error, glm::length(run.positions[f][i] - ref.positions[f][i]));
        energyError = std::max(energyError, std::abs(run.energy[f] - ref.energy[f]));
    }
    const double scale = std::abs(referenceEnergy) > 0 ? std::abs(referenceEnergy) : 1.0;
    r.set("max_position_error_m", std::isfinite(error) ? error : std::numeric_limits<double>::infinity());
    r.set("max_energy_error_relative", energyError / scale);
    r.error = r.metric("max_position_error_m");
}

/// One free node on one spring along its initial velocity, every other spring at it
/// perpendicular to that axis with a pinned far end (docs/benchmarks.md, "The oscillator
/// reference"): along the axis the node is the damped oscillator m u'' + c u' + k u = 0, u(0) = 0,
/// u'(0) = |v0|, exactly (the axis spring stays on its axis: its length is L0 -+ u); a perpendicular
/// spring of length w adds only the third-order force k_p u^3 / (2 w^2) along the axis and a
/// second-order pull u^2 / (2 w) off it, which the run reports as max_off_axis_m.
struct Oscillator {
    DampedOscillator o;
    std::uint32_t node = 0;
    glm::dvec3 start{0.0}, axis{0.0};
    double restLength = 0.0; ///< of the axis spring

    [[nodiscard]] glm::dvec3 position(double t) const { return start + axis * o.displacement(t); }
};

Oscillator oscillatorOf(const Scene& scene, const std::string& source) {
    const auto fail = [&](const std::string& what) -> Oscillator {
        throw Error(source +
                    ": the oscillator reference needs effects springs (and optionally damping) only, one "
                    "free node with an initial velocity, one spring at it along that velocity and any others "
                    "perpendicular to it, underdamped: " +
                    what);
    };
    for (Effect e : scene.effects.list())
        if (e != Effect::Springs && e != Effect::Damping)
            return fail("effect " + std::string(effectName(e)) + " is on");
    if (!scene.effects.has(Effect::Springs)) return fail("springs are off");
    const model::FlatModel m = model::flatten(scene);
    Oscillator r;
    int free = 0;
    for (std::uint32_t i = 0; i < m.nodeCount(); ++i)
        if (m.inverseMasses[i] > 0.0) r.node = i, ++free;
    if (free != 1) return fail(std::to_string(free) + " free nodes");
    const glm::dvec3 v = m.velocities[r.node];
    const double speed = glm::length(v);
    if (!(speed > 0.0)) return fail("the free node starts at rest (give the object a velocity)");
    r.start = m.positions[r.node];
    r.axis = v / speed;
    int along = 0;
    double stiffness = 0.0, damping = 0.0;
    for (const model::FlatSpring& sp : m.springs) {
        if (sp.a != r.node && sp.b != r.node) continue;
        const glm::dvec3 d = m.positions[sp.a == r.node ? sp.b : sp.a] - r.start;
        const double length = glm::length(d), c = glm::dot(d, r.axis) / length;
        if (std::abs(std::abs(c) - 1.0) <= 1e-12) {
            ++along;
            stiffness = sp.stiffness;
            damping = sp.damping;
            r.restLength = length;
        } else if (std::abs(c) > 1e-9) {
            return fail("a spring at the free node is neither along nor across the velocity (cos " +
                        std::to_string(c) + ")");
        }
    }
    if (along != 1) return fail(std::to_string(along) + " springs along the velocity");
    r.o.mass = m.masses[r.node];
    r.o.stiffness = stiffness;
    // NodeForce's air damping is -c_air m v, spring damping -c u' along the spring.
    r.o.damping = damping + (scene.effects.has(Effect::Damping) ? scene.damping * r.o.mass : 0.0);
    r.o.v0 = speed;
    if (!(r.o.zeta() < 1.0)) return fail("damping ratio " + std::to_string(r.o.zeta()) + " >= 1");
    if (!(r.o.amplitude() < r.restLength))
        return fail("amplitude " + std::to_string(r.o.amplitude()) + " m reaches the spring's pinned end");
    return r;
}

/// Fewer frames per period than this and the period and amplitude estimators are not applied.
constexpr double kMinFramesPerPeriod = 8.0;

/// The run against the closed form after every frame, and the period and amplitude decay read
/// off the trajectory along the axis (oscillator.hpp).
void compareOscillator(const Trajectory& t, const Oscillator& ref, RunResult& r) {
    const double dt = t.dt;
    std::vector<double> u{0.0}; // the node starts at the rest length
    double error = 0.0, axisError = 0.0, offAxis = 0.0, energyError = 0.0, largest = 0.0;
    int grewAt = 0;
    const double e0 = ref.o.energy(0.0);
    for (std::size_t f = 0; f < t.positions.size(); ++f) {
        const double time = double(f + 1) * dt;
        const glm::dvec3 p = t.positions[f][ref.node];
        const glm::dvec3 d = p - ref.start;
        u.push_back(glm::dot(d, ref.axis));
        error = std::max(error, glm::length(p - ref.position(time)));
        axisError = std::max(axisError, std::abs(u.back() - ref.o.displacement(time)));
        offAxis = std::max(offAxis, glm::length(d - ref.axis * u.back()));
        energyError = std::max(energyError, std::abs(t.energy[f] - ref.o.energy(time)));
        largest = std::max(largest, std::abs(u.back()));
        if (grewAt == 0 && !(std::abs(u.back()) <= 2.0 * ref.o.amplitude())) grewAt = static_cast<int>(f + 1);
    }
    const double inf = std::numeric_limits<double>::infinity();
    r.set("max_position_error_m", std::isfinite(error) ? error : inf);
    r.set("max_energy_error_relative", std::isfinite(energyError) ? energyError / e0 : inf);
    r.set("max_axis_error_m", std::isfinite(axisError) ? axisError : inf);
    r.set("max_off_axis_m", std::isfinite(offAxis) ? offAxis : inf);
    r.set("amplitude_exact_m", ref.o.amplitude());
    r.set("max_displacement_m", std::isfinite(largest) ? largest : inf);
    const double exactPeriod = ref.o.period();
    r.set("period_exact_s", exactPeriod);
    r.set("frames_per_period", exactPeriod / dt);
    r.set("amplitude_ratio_exact", ref.o.amplitudeRatioPerPeriod());
    const double runTime = double(t.positions.size()) * dt;
    r.set("energy_drift_exact_relative", (ref.o.energy(runTime) - e0) / e0);
    r.error = r.metric("max_position_error_m");
    if (grewAt != 0 && r.failure.empty())
        r.failure =
            "diverged: the displacement left twice the exact amplitude at frame " + std::to_string(grewAt);
    if (!r.failure.empty() || exactPeriod / dt < kMinFramesPerPeriod) return;
    const std::vector<double> crossings = upwardZeroCrossings(u, dt);
    if (crossings.size() < 3) return; // two full periods at least
    const double period = meanPeriod(crossings);
    const std::vector<double> peaks = periodPeaks(u, dt, crossings);
    const double ratio = meanAmplitudeRatio(peaks);
    r.set("periods_measured", double(crossings.size() - 1));
    r.set("period_s", period);
    r.set("period_error_relative", (period - exactPeriod) / exactPeriod);
    // The sampling resolution of the measured period: two crossing times, each within the linear
    // interpolation's bound for the measured curve (its own frequency and decay).
    const double measuredOmega = 2.0 * std::numbers::pi / period;
    const double measuredDecay = ratio > 0.0 ? std::max(0.0, -std::log(ratio) / period) : 0.0;
    r.set("period_resolution_s",
          2.0 * crossingTimeBound(measuredOmega, measuredDecay, dt) / double(crossings.size() - 1));
    r.set("amplitude_ratio_per_period", ratio);
    // Each peak's relative bias is the same function of its sampling phase (the curve repeats
    // scaled by the ratio), so the ratio is off by at most twice the bound over the periods.
    r.set("amplitude_ratio_resolution",
          peaks.size() >= 2
              ? 2.0 * peakBound(measuredOmega, measuredDecay, dt) * ratio / double(peaks.size() - 1)
              : kNaN);
    // Simulated amplitude lost per period minus the exact loss: (1 - ratio) - (1 - exact).
    r.set("numerical_damping_per_period", ref.o.amplitudeRatioPerPeriod() - ratio);
}

void integration(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "GPU ms per frame";
    out.errorLabel = "largest node position error (m)";
    bool coarse = false;
    for (const SceneEntry& s : x.scenes) {
        Trajectory ref;
        double referenceEnergy = 0.0;
        std::optional<Oscillator> oscillator;
        if (x.reference == IntegrationReference::Ballistic) {
            const Scene scene = buildScene(s, x.configs.front());
            const Ballistic o = ballisticOf(scene, s.source);
            const double dt = scene.time.dt;
            for (int f = 1; f <= x.warmupFrames + x.frames; ++f) {
                ref.positions.push_back(o.positions(f * dt));
                ref.energy.push_back(o.energy());
            }
            referenceEnergy = o.energy();
        } else if (x.reference == IntegrationReference::Oscillator) {
            oscillator = oscillatorOf(buildScene(s, x.configs.front()), s.source);
        } else {
            ConfigEntry refConfig = x.configs.front();
            Scene base = buildScene(s, refConfig);
            applySubstepFactor(base, refConfig.substepFactor);
            const int baseSubsteps = base.time.substeps != 0
                                         ? base.time.substeps
                                         : Engine(base, {.gpuTiming = false}).substepInfo().substeps;
            refConfig.name = "reference";
            refConfig.substepFactor = 1;
            progress(s.name + " / reference (" + std::to_string(x.referenceFactor) + " x " +
                     std::to_string(baseSubsteps) + " substeps)");
            base.time.substeps = baseSubsteps * x.referenceFactor;
            Engine engine(base);
            referenceEnergy = engine.energy().total();
            RunResult r = measureRun(engine, x, recordTrajectory(ref));
            if (!r.failure.empty()) throw Error(s.source + ": the converged reference run " + r.failure);
        }
        for (const ConfigEntry& c : x.configs) {
            progress(s.name + " / " + c.name);
            Trajectory t;
            RunResult r = runScene(x, s, c, recordTrajectory(t), nullptr, recordStart(t));
            if (oscillator) {
                // Every configuration must describe the same oscillator (a config may change the
                // integrator or the substeps, not the body).
                const Oscillator o =
                    oscillatorOf(buildScene(s, c), s.source + " (config \"" + c.name + "\")");
                if (o.o.mass != oscillator->o.mass || o.o.stiffness != oscillator->o.stiffness ||
                    o.o.damping != oscillator->o.damping || o.o.v0 != oscillator->o.v0 ||
                    o.node != oscillator->node)
                    throw Error(
                        s.source + " (config \"" + c.name +
                        "\"): the configuration changes the oscillator (mass, spring, damping or velocity)");
                compareOscillator(t, *oscillator, r);
                coarse = coarse || r.metric("frames_per_period") < kMinFramesPerPeriod;
            } else {
                compareTrajectories(t, ref, referenceEnergy, r);
            }
            addCostAndDrift(t, r);
            r.time = r.gpuMs.median;
            out.runs.push_back(std::move(r));
        }
    }
    if (x.reference == IntegrationReference::Ballistic)
        out.notes.push_back(
            "Ground truth: the closed-form free flight x(t) = x0 + v0 t + g t^2/2 of every node (springs at "
            "rest), compared after every frame; energy error relative to the constant exact energy.");
    else if (x.reference == IntegrationReference::Converged)
        out.notes.push_back(
            "Ground truth: the same scene at " + std::to_string(x.referenceFactor) +
            " x the first configuration's substeps (converged reference), compared after every frame.");
    else {
        out.notes.push_back(
            "Ground truth: the damped oscillator m u'' + c u' + k u = 0, u(0) = 0, u'(0) = v0 of the "
            "one free node along its spring (m its lumped mass, c spring + air damping), compared "
            "after every frame. max_position_error_m is the node's distance from the closed form, "
            "max_axis_error_m its part along the spring; max_off_axis_m, the motion across it, is "
            "the perpendicular springs' second-order pull and float rounding of their length, not "
            "the integrator.");
        out.notes.push_back(
            "Period: mean spacing of the upward zero crossings of the displacement sampled once per frame "
            "(linear interpolation between frames; period_resolution_s bounds that interpolation's error). "
            "Amplitude ratio: geometric mean of consecutive per-period peaks (3-point parabola), numerical "
            "damping = exact ratio e^(-zeta omega T_d) minus simulated ratio = amplitude lost per period "
            "beyond the physical loss.");
        if (coarse)
            out.notes.push_back(
                "Scenes with fewer than 8 frames per period report no period or amplitude ratio "
                "(n/a): frame sampling cannot resolve them; their error and energy drift stand.");
    }
    out.notes.push_back(
        "Cost: GPU (and wall) ms per simulated second = ms per frame / dt. Energy drift: total energy "
        "(kinetic + gravity + springs) after the last frame minus before the first, relative to the "
        "first (its zero is the scene's: gravity's potential is 0 at y = 0).");
    out.notes.push_back(
        "Configurations differ in substeps per frame (and in the integrator where a configuration sets "
        "one); a run whose state went non-finite is reported as diverged.");
}

void contact(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "GPU ms per frame";
    out.errorLabel = "deepest penetration (m)";
    for (const SceneEntry& s : x.scenes)
        for (const ConfigEntry& c : x.configs) {
            progress(s.name + " / " + c.name);
            const FaceData d = faceData(buildScene(s, c));
            cpu::Penetration deepest;
            const FrameHook hook = [&](Engine& e, int) {
                const cpu::Penetration p = cpu::deepestPenetration(d.model.faceIndices, d.faceObject,
                                                                   d.nodeObject, e.readPositions(), d.closed);
                if (p.depth > deepest.depth) deepest = p;
            };
            RunResult r = runScene(x, s, c, hook);
            r.set("deepest_penetration_m", deepest.depth);
            r.time = r.gpuMs.median;
            r.error = deepest.depth;
            out.runs.push_back(std::move(r));
        }
    out.notes.push_back(
        "Penetration: after every frame, the deepest node of one body strictly inside another closed "
        "body (generalised winding number), measured as its distance to that body's surface, in "
        "double precision on the read-back state. max_intersecting_pairs is the largest count of "
        "exactly intersecting face pairs (robust narrow phase) over all substeps.");
}

} // namespace

ExperimentResult runExperiment(const Experiment& experiment, const Progress& progress) {
    ExperimentResult out;
    out.experiment = experiment;
    std::size_t done = 0;
    const std::size_t total = experiment.kind == ExperimentKind::Bvh ? bvhRunCount(experiment)
                              : experiment.kind == ExperimentKind::Ccd
                                  ? ccdRunCount(experiment)
                                  : experiment.scenes.size() * experiment.configs.size() +
                                        experiment.caseFamilies.size() * experiment.configs.size();
    const Progress counted = [&](const std::string& what) {
        if (progress)
            progress(experiment.name + " " + std::to_string(std::min(++done, total)) + "/" +
                     std::to_string(total) + ": " + what);
    };
    switch (experiment.kind) {
    case ExperimentKind::Scaling:
        scaling(experiment, out, counted);
        break;
    case ExperimentKind::BroadPhase:
        broadOrNarrow(experiment, out, counted, true);
        break;
    case ExperimentKind::NarrowPhase:
        narrowPhase(experiment, out, counted);
        break;
    case ExperimentKind::Integration:
        integration(experiment, out, counted);
        break;
    case ExperimentKind::Contact:
        contact(experiment, out, counted);
        break;
    case ExperimentKind::Bvh:
        runBvhExperiment(experiment, out, counted);
        break;
    case ExperimentKind::Ccd:
        runCcdExperiment(experiment, out, counted);
        break;
    case ExperimentKind::Response:
        runResponseExperiment(experiment, out, counted);
        break;
    }
    return out;
}

} // namespace glcollide::benchkit
