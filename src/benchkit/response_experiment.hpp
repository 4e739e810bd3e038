#pragma once
/// \file The `response` experiment (docs/benchmarks.md, "The response experiment"): the contact
/// responses (penalty, bridson, intersection_free) against the step size on contact scenes. Per
/// run: the most exactly intersecting face pairs at the start of any substep (the engine's robust
/// TriTri; 0 is the intersection-free response's guarantee), the total energy's drift and largest
/// rise from one frame to the next, how often the safe step acted, solver iterations, and wall
/// and GPU ms per substep.

#include "benchkit/experiments.hpp"

#include <vector>

namespace glcollide::benchkit {

/// Appends one run per scene x configuration to `out`, with its notes.
void runResponseExperiment(const Experiment& experiment, ExperimentResult& out, const Progress& progress);

/// The energy of a run: before the first frame, then after every frame.
struct EnergyDrift {
    double start = 0.0, end = 0.0;
    double drift = 0.0;   ///< end - start
    double maxRise = 0.0; ///< the largest E(k) - E(k-1) over the frames; 0 when it never rose
    int maxRiseFrame = 0; ///< the frame k of that rise (0: none)
};

/// Drift and largest rise of the series `energy` = {E(0), E(1), ...}; all 0 for an empty series.
EnergyDrift energyDrift(const std::vector<double>& energy);

} // namespace glcollide::benchkit
