#include "benchkit/response_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glcollide::benchkit {
namespace {

/// What a run's frames add up to beyond measureRun's timings (warm-up frames included: the
/// simulation starts at frame 1 whatever is timed).
struct ResponseTally {
    std::vector<double> energy;     ///< E(0), E(1), ...
    std::vector<double> resolution; ///< EnergyReport::resolution of each of them
    std::vector<double> ambiguity;  ///< EnergyReport::contactAmbiguity of each of them
    double substeps = 0, safeStepSubsteps = 0, safeStepCuts = 0, safeStepFrozeAll = 0;
    double safeStepMaxRounds = 0, groundCrossings = 0, substepsWithIntersections = 0;
    double solverIterations = 0, solverMaxIterations = 0, unconvergedSubsteps = 0;
    double guardSubsteps = 0, guardPulledBack = 0, guardBackToStart = 0, guardRemoved = 0;
    double lineSearchSteps = 0, lineSearchShortened = 0, lineSearchRejected = 0;
    bool lineSearch = false;
    int substepsPerFrame = 1;
    bool safeStep = false, implicit = false, guard = false;

    void addEnergy(const EnergyReport& e) {
        energy.push_back(e.total());
        resolution.push_back(e.resolution);
        ambiguity.push_back(e.contactAmbiguity);
    }
};

FrameHook tallyFrames(ResponseTally& t) {
    return [&t](Engine& e, int) {
        const StepStats& s = e.lastStep();
        t.addEnergy(e.energy());
        t.substeps += s.substeps;
        t.substepsPerFrame = s.substeps;
        t.safeStep = t.safeStep || s.safeStep;
        t.implicit = s.solver.implicit;
        if (s.collisions) t.substepsWithIntersections += s.collision.substepsWithIntersections;
        if (s.safeStep) {
            t.safeStepSubsteps += s.collision.safeStepSubsteps;
            t.safeStepCuts += s.collision.safeStepCuts;
            t.safeStepFrozeAll += s.collision.safeStepFrozeAll;
            t.groundCrossings += s.collision.safeStepGroundCrossings;
            t.safeStepMaxRounds = std::max(t.safeStepMaxRounds, double(s.collision.safeStepMaxRounds));
        }
        if (s.collision.energyGuard) {
            t.guard = true;
            t.guardSubsteps += s.collision.energyGuardSubsteps;
            t.guardPulledBack += s.collision.energyGuardPulledBack;
            t.guardBackToStart += s.collision.energyGuardBackToStart;
            t.guardRemoved += s.collision.energyGuardRemoved;
        }
        t.solverIterations += s.solver.totalIterations;
        t.solverMaxIterations = std::max(t.solverMaxIterations, double(s.solver.maxIterations));
        t.unconvergedSubsteps += s.solver.unconvergedSubsteps;
        t.lineSearch = t.lineSearch || s.solver.lineSearch;
        t.lineSearchSteps += s.solver.lineSearchSteps;
        t.lineSearchShortened += s.solver.lineSearchShortened;
        t.lineSearchRejected += s.solver.lineSearchRejected;
    };
}

void record(const ResponseTally& t, RunResult& r) {
    const EnergyDrift d = energyDrift(t.energy);
    r.set("energy_start_j", d.start);
    r.set("energy_end_j", d.end);
    r.set("energy_drift_j", d.drift);
    r.set("energy_max_rise_j", d.maxRise);
    r.set("energy_max_rise_frame", d.maxRiseFrame);
    r.set("substeps_with_intersections", t.substepsWithIntersections);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // The safe step exists only in the intersection-free response: n/a for the others.
    r.set("safe_step_substeps", t.safeStep ? t.safeStepSubsteps : nan);
    r.set("safe_step_fraction", t.safeStep && t.substeps > 0 ? t.safeStepSubsteps / t.substeps : nan);
    r.set("safe_step_node_cuts", t.safeStep ? t.safeStepCuts : nan);
    r.set("safe_step_max_rounds", t.safeStep ? t.safeStepMaxRounds : nan);
    r.set("safe_step_froze_all", t.safeStep ? t.safeStepFrozeAll : nan);
    r.set("safe_step_ground_crossings", t.safeStep ? t.groundCrossings : nan);
    // The energy guard: how often it acted, and the largest frame rise against what the guard's
    // float sums allow a frame (2·substeps·(resolution at its start + at its end), plus the contact
    // energy a float evaluation may count differently at either end, the bound
    // tests/gl/intersection_free_gl_test.cpp checks): at most 1 when the promise holds.
    const bool guard = t.guard && t.substeps > 0;
    r.set("energy_guard_fraction", guard ? t.guardSubsteps / t.substeps : nan);
    r.set("energy_guard_pull_back_fraction", guard ? t.guardPulledBack / t.substeps : nan);
    // Pulled all the way back to the start at rest: the scene stood still for that substep (a run of
    // them is a freeze, which the other fractions do not tell from a shortened step).
    r.set("energy_guard_back_to_start_fraction", guard ? t.guardBackToStart / t.substeps : nan);
    r.set("energy_guard_removed_j", guard ? t.guardRemoved : nan);
    double worst = 0.0;
    for (std::size_t k = 1; k < t.energy.size(); ++k) {
        const double allowance = 2.0 * t.substepsPerFrame * (t.resolution[k - 1] + t.resolution[k]) +
                                 t.ambiguity[k - 1] + t.ambiguity[k];
        const double rise = t.energy[k] - t.energy[k - 1];
        if (rise > 0.0)
            worst =
                std::max(worst, allowance > 0.0 ? rise / allowance : std::numeric_limits<double>::infinity());
    }
    r.set("energy_rise_over_allowance", guard ? worst : nan);
    r.set("solver_iterations_per_substep",
          t.implicit && t.substeps > 0 ? t.solverIterations / t.substeps : nan);
    r.set("solver_max_iterations", t.implicit ? t.solverMaxIterations : nan);
    r.set("solver_unconverged_substeps", t.implicit ? t.unconvergedSubsteps : nan);
    // The Newton steps' line search: the fraction of searched steps it shortened / rejected.
    const bool search = t.lineSearch && t.lineSearchSteps > 0;
    r.set("line_search_steps", t.lineSearch ? t.lineSearchSteps : nan);
    r.set("line_search_shortened_fraction", search ? t.lineSearchShortened / t.lineSearchSteps : nan);
    r.set("line_search_rejected_fraction", search ? t.lineSearchRejected / t.lineSearchSteps : nan);
    // Newton steps taken per substep: the first solve and each line-searched further step (steps
    // after a converged one are not taken: time.solver.newton_tolerance).
    r.set("newton_steps_per_substep",
          t.lineSearch && t.substeps > 0 ? 1.0 + t.lineSearchSteps / t.substeps : nan);
    r.set("wall_ms_per_substep", r.wallMs.median / r.substeps);
    r.set("gpu_ms_per_substep", r.gpuMs.median / r.substeps);
}

} // namespace

EnergyDrift energyDrift(const std::vector<double>& energy) {
    EnergyDrift d;
    if (energy.empty()) return d;
    d.start = energy.front();
    d.end = energy.back();
    d.drift = d.end - d.start;
    for (std::size_t k = 1; k < energy.size(); ++k)
        if (energy[k] - energy[k - 1] > d.maxRise) {
            d.maxRise = energy[k] - energy[k - 1];
            d.maxRiseFrame = static_cast<int>(k);
        }
    return d;
}

void runResponseExperiment(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "wall ms per substep";
    out.errorLabel = "max intersecting pairs";
    out.errorIsCount = true;
    for (const SceneEntry& s : x.scenes)
        for (const ConfigEntry& c : x.configs) {
            progress(s.name + " / " + c.name);
            Scene scene = buildScene(s, c);
            applySubstepFactor(scene, c.substepFactor);
            Engine engine(scene);
            ResponseTally tally;
            tally.addEnergy(engine.energy());
            RunResult r = measureRun(engine, x, tallyFrames(tally));
            r.scene = s.name;
            r.config = c.name;
            record(tally, r);
            r.time = r.metric("wall_ms_per_substep");
            r.error = r.metric("max_intersecting_pairs");
            out.runs.push_back(std::move(r));
        }
    out.notes.push_back(
        "Over all frames (warm-up included; times over the measured frames only): max_intersecting_pairs "
        "is the most exactly intersecting face pairs (robust TriTri) at the start of any substep, and "
        "must be 0 under intersection_free; energy (kinetic + gravity + springs, and for intersection_free "
        "the penalty contacts, J, from the read-back "
        "state) before the first frame, after the last, and the largest "
        "rise from one frame to the next (0: never rose).");
    out.notes.push_back(
        "Safe step (intersection_free only): the fraction of substeps in which it cut any node's step, "
        "node steps cut, most cut-and-check rounds in a substep, and substeps where every node was "
        "frozen (froze_all). Penalty and bridson run with discrete detection, intersection_free with "
        "continuous detection.");
    out.notes.push_back(
        "Energy guard (intersection_free only): the fraction of substeps in which it acted and in which "
        "it pulled the step back; rise / allowance is the largest frame-to-frame rise over what the "
        "guard's float sums allow the frame (2 x substeps x the resolution at both ends, plus the contact "
        "energy a float evaluation may count differently, EnergyReport::contactAmbiguity): at most 1 "
        "when no energy was gained.");
}

} // namespace glcollide::benchkit
