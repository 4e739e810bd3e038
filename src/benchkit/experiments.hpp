#pragma once
/// \file Runs the experiments of a suite on the current GL context: each scene under each
/// configuration, timed per pass, and compared with the experiment's ground truth.

#include "benchkit/results.hpp"
#include "benchkit/suite.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <functional>
#include <string>

namespace glcollide::benchkit {

/// Receives one line per run ("broad_phase 3/10: two boxes / octree d2") for stderr.
using Progress = std::function<void(const std::string&)>;

/// Runs every scene x configuration of `experiment` (and, for narrow_phase, every case family x
/// configuration). Problems with a run that are not setup errors (a simulation that diverges)
/// are recorded in RunResult::failure; setup errors (bad scenes) throw glcollide::Error.
ExperimentResult runExperiment(const Experiment& experiment, const Progress& progress);

// Pieces the experiments share (experiments.cpp).

/// The scene of `entry` with the configuration's merge patch applied, parsed (and so validated)
/// by the scene reader; errors name the scene's source and the configuration.
Scene buildScene(const SceneEntry& entry, const ConfigEntry& config);

/// Multiplies the scene's substeps per frame (its explicit count, or the automatic one).
void applySubstepFactor(Scene& scene, int factor);

/// Called after every frame (warm-up included) with the 1-based frame number.
using FrameHook = std::function<void(Engine&, int frame)>;

/// Steps warm-up frames, then measured frames, collecting per-pass GPU time and wall time (of
/// the measured frames) and the largest intersecting-pair count (of all frames).
RunResult measureRun(Engine& engine, const Experiment& experiment, const FrameHook& hook);

} // namespace glcollide::benchkit
