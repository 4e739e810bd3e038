#include "app/commands.hpp"
#include "app/mesh_export.hpp"
#include "app/progress.hpp"
#include "app/self_check_report.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>
#include <glcollide/scene.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <iostream>

namespace glcollide::app {
namespace {

nlohmann::json frameRecord(const Engine& engine) {
    const StepStats& s = engine.lastStep();
    const EnergyReport e = engine.energy();
    nlohmann::json gpu = nlohmann::json::object();
    for (const PassTiming& p : s.passes) gpu[p.name] = p.gpuMilliseconds;
    nlohmann::json record = {{"frame", s.frame},
                             {"time_s", s.time},
                             {"wall_ms", s.wallMilliseconds},
                             {"kinetic_energy_J", e.kinetic},
                             {"potential_energy_J", e.potential},
                             {"contact_energy_J", e.contact},
                             {"total_energy_J", e.total()},
                             {"energy_resolution_J", e.resolution},
                             {"dispatches_per_substep", s.dispatchesPerSubstep},
                             {"gpu_ms", gpu}};
    if (s.solver.implicit)
        record["solver"] = {{"max_iterations", s.solver.maxIterations},
                            {"max_relative_residual", s.solver.maxRelativeResidual},
                            {"total_iterations", s.solver.totalIterations},
                            {"unconverged_substeps", s.solver.unconvergedSubsteps}};
    if (s.solver.lineSearch) {
        record["solver"]["line_search"] = {{"steps", s.solver.lineSearchSteps},
                                           {"shortened", s.solver.lineSearchShortened},
                                           {"rejected", s.solver.lineSearchRejected}};
        record["solver"]["newton_steps_skipped"] = s.solver.newtonStepsSkipped;
    }
    if (s.collisions) {
        const CollisionStats& c = s.collision;
        record["collision"] = {{"box_pairs", c.boxPairs},
                               {"candidate_pairs", c.candidatePairs},
                               {"intersecting_pairs", c.intersectingPairs},
                               {"max_intersecting_pairs", c.maxIntersectingPairs},
                               {"contacts", c.contacts},
                               {"undecided_pairs", c.undecidedPairs},
                               {"exact_fallbacks", c.exactFallbacks},
                               {"list_growths", c.listGrowths},
                               {"vertex_face_pairs", c.vertexFacePairs},
                               {"edge_edge_pairs", c.edgeEdgePairs},
                               {"vertex_face_pairs_without_ownership", c.vertexFacePairsWithoutOwnership},
                               {"edge_edge_pairs_without_ownership", c.edgeEdgePairsWithoutOwnership},
                               {"bvh_node_visits", c.bvhNodeVisits},
                               {"bvh_rebuilds", c.bvhRebuilds},
                               {"bvh_rounds", c.bvhRounds}};
        if (s.continuous) {
            // The earliest time of impact as a fraction of a substep; null when nothing may touch.
            const nlohmann::json earliest =
                std::isfinite(c.ccdEarliestToi) ? nlohmann::json(c.ccdEarliestToi) : nlohmann::json(nullptr);
            record["ccd"] = {{"swept_candidate_pairs", c.candidatePairs},
                             {"vertex_face_pairs_tested", c.vertexFacePairs},
                             {"edge_edge_pairs_tested", c.edgeEdgePairs},
                             {"vertex_face_may_touch", c.ccdVertexFaceHits},
                             {"edge_edge_may_touch", c.ccdEdgeEdgeHits},
                             {"capped_pairs", c.ccdCapped},
                             {"capped_pairs_in_frame", c.ccdCappedInFrame},
                             {"boxes", c.ccdBoxes},
                             {"earliest_toi", earliest}};
        }
        if (s.safeStep)
            record["safe_step"] = {{"substeps_cut", c.safeStepSubsteps},
                                   {"node_steps_cut", c.safeStepCuts},
                                   {"max_rounds", c.safeStepMaxRounds},
                                   {"froze_all", c.safeStepFrozeAll},
                                   {"ground_crossings", c.safeStepGroundCrossings}};
        record["collision"]["substeps_with_intersections"] = c.substepsWithIntersections;
        // Recovery from intersecting input: null until a substep begins intersection-free.
        record["collision"]["substeps_until_intersection_free"] =
            c.reachedIntersectionFree ? nlohmann::json(c.substepsUntilIntersectionFree)
                                      : nlohmann::json(nullptr);
        if (s.safeStep) {
            record["safe_step"]["ccd_pairs_left_out_intersecting"] = c.ccdTangledPairs;
            record["safe_step"]["untangle"] = {{"substeps", c.untangleSubsteps},
                                               {"node_steps", c.untangledNodes},
                                               {"pairs_without_segment", c.untangleUnresolvedPairs}};
        }
        if (c.radialObservedFaces > 0)
            record["radial_culling"] = {{"substeps_culled", c.radialSubsteps},
                                        {"observed_faces", c.radialObservedFaces},
                                        {"non_positive_faces", c.radialNonPositiveFaces},
                                        {"free_faces", c.radialFreeFaces},
                                        {"ghost_faces", c.radialGhostFaces},
                                        {"violated_surfaces", c.radialViolatedSurfaces},
                                        {"substeps_violated", c.radialSubstepsViolated},
                                        {"tri_tri_pairs_left_out", c.radialCulledTriTri},
                                        {"ccd_pairs_left_out", c.radialCulledCcd},
                                        {"tri_tri_pairs_left_out_in_frame", c.radialCulledTriTriInFrame},
                                        {"ccd_pairs_left_out_in_frame", c.radialCulledCcdInFrame}};
        if (c.radialStartChecked) record["radial_culling"]["start_free"] = c.radialStartFree;
        if (c.energyGuard)
            record["energy_guard"] = {{"substeps_acted", c.energyGuardSubsteps},
                                      {"substeps_pulled_back", c.energyGuardPulledBack},
                                      {"substeps_back_to_start", c.energyGuardBackToStart},
                                      {"removed_J", c.energyGuardRemoved},
                                      {"unremoved_J", c.energyGuardUnremoved},
                                      {"largest_rise_J", c.energyGuardLargestRise}};
    }
    return record;
}

bool allFinite(const std::vector<glm::dvec3>& positions, std::size_t& firstBad) {
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) ||
            !std::isfinite(positions[i].z)) {
            firstBad = i;
            return false;
        }
    return true;
}

nlohmann::json nonFiniteRecord(const Engine& engine) {
    const NonFiniteReport& r = engine.lastStep().nonFinite;
    if (!r.found) return nullptr;
    return {{"frame", r.frame},   {"substep", r.substep},
            {"object", r.object}, {"object_name", engine.scene().bodies[r.object].name},
            {"node", r.node},     {"global_node", r.globalNode}};
}

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

// The "setup" object of --stats: what building the compute programs cost (docs/cli.md, --stats).
nlohmann::json setupRecord(const SetupStats& s) {
    nlohmann::json programs = nlohmann::json::array();
    for (const ProgramSetup& p : s.programs)
        programs.push_back({{"shader", p.shader},
                            {"defines", p.defines},
                            {"source_fnv1a64", hex64(p.sourceHash)},
                            {"ms", p.milliseconds},
                            {"cache", p.cacheHit ? "hit" : "miss"}});
    nlohmann::json cache = {
        {"hits", s.cacheHits},
        {"misses", s.cacheMisses},
        {"folder", s.cacheFolder.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.cacheFolder)}};
    if (!s.cacheNote.empty()) cache["note"] = s.cacheNote;
    return {{"compile_link_ms", s.compileLinkMilliseconds},
            {"program_cache", cache},
            {"programs", programs},
            {"robust_self_check", selfCheckJson(s.robustSelfCheck)}};
}

void printSummary(const HeadlessContext& context, const Engine& engine, std::uint64_t frames) {
    const Scene& scene = engine.scene();
    const SubstepInfo& sub = engine.substepInfo();
    std::cout << "scene: " << scene.name
              << (scene.sourcePath.empty() ? " (built-in default)" : " (" + scene.sourcePath.string() + ")")
              << "\n"
              << "device: " << context.deviceDescription() << " | " << context.glInfo().renderer << "\n"
              << "bodies: " << scene.bodies.size() << "  nodes: " << engine.nodeCount()
              << "  springs: " << engine.springCount() << "  faces: " << engine.faceCount() << "\n";
    std::cout << "effects:";
    for (Effect e : scene.effects.list()) std::cout << ' ' << effectName(e);
    std::cout << "\npipeline (per substep):";
    for (const std::string& p : engine.pipeline()) std::cout << ' ' << p;
    std::cout << "\nbuffers:";
    for (const std::string& b : engine.allocatedBuffers()) std::cout << ' ' << b;
    std::cout << " (" << engine.allocatedBytes() << " bytes)\n";
    if (scene.time.integrator == Integrator::ImplicitEuler) {
        const double perNode =
            engine.nodeCount() ? static_cast<double>(engine.solverBytes()) / engine.nodeCount() : 0.0;
        std::cout << "solver: implicit Euler, conjugate gradients to " << scene.time.solver.tolerance
                  << " relative residual or " << scene.time.solver.maxIterations << " iterations; "
                  << engine.solverBytes() << " bytes (" << perNode << " per node)\n";
        std::cout << "time: " << frames << " frames of " << scene.time.dt << " s, " << sub.substeps
                  << " substeps each (" << (sub.automatic ? "auto" : "fixed")
                  << "; symplectic Euler would need " << sub.stableSubsteps << ")\n";
    } else {
        std::cout << "time: " << frames << " frames of " << scene.time.dt << " s, " << sub.substeps
                  << " substeps each (" << (sub.automatic ? "auto" : "fixed") << "; stability needs "
                  << sub.stableSubsteps << ")\n";
    }
    const SetupStats& setup = engine.setupStats();
    std::cout << "setup: " << setup.programs.size() << " programs in " << setup.compileLinkMilliseconds
              << " ms (program cache: " << setup.cacheHits << " hits, " << setup.cacheMisses << " misses, "
              << (setup.cacheFolder.empty() ? "off" : setup.cacheFolder);
    if (!setup.cacheNote.empty()) std::cout << "; " << setup.cacheNote;
    std::cout << ")\n";
    if (setup.robustSelfCheck.needed)
        std::cout << "robust self-check: " << selfCheckLine(setup.robustSelfCheck) << "\n";
}

} // namespace

int runCommand(const RunOptions& options) {
    Scene scene = options.scenePath.empty() ? defaultScene() : loadScene(options.scenePath);
    if (options.frames) {
        if (*options.frames <= 0) throw Error("--frames must be positive");
        scene.time.frames = *options.frames;
    }
    if (!options.broadPhase.empty()) overrideBroadPhase(scene, options.broadPhase);
    if (options.exportEvery <= 0) throw Error("--every must be positive");
    const MeshFormat format = parseMeshFormat(options.exportFormat);
    if (!options.exportDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(options.exportDir, ec);
        if (ec) throw Error(options.exportDir + ": cannot create export directory: " + ec.message());
    }

    HeadlessContext context({options.device});
    EngineOptions engineOptions;
    engineOptions.gpuTiming = options.gpuTiming;
    engineOptions.frameStep = options.frameStep;
    Engine engine(scene, engineOptions);
    const auto frames = static_cast<std::uint64_t>(scene.time.frames);
    printSummary(context, engine, frames);
    for (const std::string& w : engine.warnings()) std::cerr << "glcollide: warning: " << w << "\n";

    const std::vector<std::uint32_t> firstNodes = engine.bodyFirstNodes();
    auto exportFrame = [&](std::uint64_t frame) {
        const auto path = std::filesystem::path(options.exportDir) / frameFileName(frame, format);
        writeFrameMesh(path, format, engine.scene(), firstNodes, engine.readPositions());
    };
    if (!options.exportDir.empty()) exportFrame(0);

    nlohmann::json stats;
    nlohmann::json frameList = nlohmann::json::array();
    Progress progress("glcollide run", frames, !options.quiet);
    double wallTotal = 0.0;
    std::uint32_t maxIntersecting = 0, maxContacts = 0;
    SolverStats solverTotals; // most iterations / residual of any substep; summed iterations, misses
    for (std::uint64_t f = 1; f <= frames; ++f) {
        engine.step();
        const SolverStats& solver = engine.lastStep().solver;
        solverTotals.maxIterations = std::max(solverTotals.maxIterations, solver.maxIterations);
        solverTotals.maxRelativeResidual =
            std::max(solverTotals.maxRelativeResidual, solver.maxRelativeResidual);
        solverTotals.totalIterations += solver.totalIterations;
        solverTotals.unconvergedSubsteps += solver.unconvergedSubsteps;
        const NonFiniteReport& nonFinite = engine.lastStep().nonFinite;
        if (nonFinite.found && nonFinite.frame == f)
            std::cerr << "glcollide: warning: non-finite position at frame " << nonFinite.frame << " substep "
                      << nonFinite.substep + 1 << " of " << engine.lastStep().substeps << ", object '"
                      << engine.scene().bodies[nonFinite.object].name << "' (" << nonFinite.object
                      << ") node " << nonFinite.node
                      << ": the simulation diverged (substeps below the stability limit?)\n";
        wallTotal += engine.lastStep().wallMilliseconds;
        maxIntersecting = std::max(maxIntersecting, engine.lastStep().collision.maxIntersectingPairs);
        maxContacts = std::max(maxContacts, engine.lastStep().collision.contacts);
        if (!options.statsPath.empty()) frameList.push_back(frameRecord(engine));
        if (!options.exportDir.empty() && f % static_cast<std::uint64_t>(options.exportEvery) == 0)
            exportFrame(f);
        progress.update(f);
    }
    progress.finish();

    const std::vector<glm::dvec3> finalPositions = engine.readPositions();
    std::size_t bad = 0;
    const bool diverged = engine.lastStep().nonFinite.found;
    const bool finite = allFinite(finalPositions, bad) && !diverged;
    if (!options.statsPath.empty()) {
        stats["scene"] = scene.name;
        stats["scene_file"] = scene.sourcePath.string();
        stats["device"] = context.deviceDescription();
        stats["gl_renderer"] = context.glInfo().renderer;
        stats["gl_version"] = context.glInfo().version;
        stats["nodes"] = engine.nodeCount();
        stats["springs"] = engine.springCount();
        stats["faces"] = engine.faceCount();
        stats["pipeline"] = engine.pipeline();
        stats["buffers"] = engine.allocatedBuffers();
        stats["allocated_bytes"] = engine.allocatedBytes();
        stats["integrator"] = integratorName(scene.time.integrator);
        stats["solver_bytes"] = engine.solverBytes();
        stats["dt_s"] = scene.time.dt;
        stats["substeps"] = engine.substepInfo().substeps;
        stats["stable_substeps"] = engine.substepInfo().stableSubsteps;
        stats["setup"] = setupRecord(engine.setupStats());
        stats["finite"] = finite;
        stats["non_finite"] = nonFiniteRecord(engine);
        stats["frames"] = frameList;
        std::ofstream out(options.statsPath);
        if (!out) throw Error(options.statsPath + ": cannot open for writing");
        out << stats.dump(1) << "\n";
        if (!out) throw Error(options.statsPath + ": write failed");
    }
    std::cout << "simulated " << frames << " frames in " << wallTotal << " ms ("
              << (frames ? wallTotal / static_cast<double>(frames) : 0.0) << " ms/frame; "
              << engine.lastStep().dispatchesPerSubstep << " dispatches per substep)\n";
    if (engine.lastStep().solver.implicit) {
        const double substepsRun = static_cast<double>(frames) * engine.lastStep().substeps;
        std::cout << "solver: " << (substepsRun > 0 ? solverTotals.totalIterations / substepsRun : 0.0)
                  << " iterations per substep on average (all its Newton steps), at most "
                  << solverTotals.maxIterations << " in one solve; largest final relative residual "
                  << solverTotals.maxRelativeResidual << "; " << solverTotals.unconvergedSubsteps
                  << " solves stopped at the cap\n";
    }
    if (engine.lastStep().collisions)
        std::cout << "collisions: at most " << maxContacts << " contacts and " << maxIntersecting
                  << " intersecting face pairs in a substep; "
                  << engine.lastStep().collision.intersectingPairs << " intersecting at the end\n";
    if (!finite) {
        std::cerr << "glcollide: error: the state became non-finite (first at ";
        if (diverged)
            std::cerr << "frame " << engine.lastStep().nonFinite.frame << ", node "
                      << engine.lastStep().nonFinite.globalNode;
        else
            std::cerr << "node " << bad;
        std::cerr << "); lower /time/dt or use automatic substeps\n";
        return 3;
    }
    return 0;
}

} // namespace glcollide::app
