#pragma once
/// \file Runs the experiments of a suite on the current GL context: each scene under each
/// configuration, timed per pass, and compared with the experiment's ground truth.

#include "benchkit/results.hpp"
#include "benchkit/suite.hpp"

#include <functional>
#include <string>

namespace glcollide::benchkit {

/// Receives one line per run ("broad_phase 3/10: two boxes / octree d2") for stderr.
using Progress = std::function<void(const std::string&)>;

/// Runs every scene x configuration of `experiment` (and, for narrow_phase, every case family x
/// configuration). Problems with a run that are not setup errors (a simulation that diverges)
/// are recorded in RunResult::failure; setup errors (bad scenes) throw glcollide::Error.
ExperimentResult runExperiment(const Experiment& experiment, const Progress& progress);

} // namespace glcollide::benchkit
