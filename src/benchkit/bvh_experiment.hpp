#pragma once
/// \file The `bvh` experiment (docs/benchmarks.md, "The bvh experiment"): the linear BVH broad
/// phase against the octree on self-colliding folded cloth (benchkit/folded_cloth.hpp) at the
/// seed's Tables 1-3 sizes and at sizes growing to ~1M faces, and on mesh scenes (cloth_ball92).
/// Per configuration and scene: per-pass GPU time of one substep's collision detection (median of
/// the measured repetitions), candidates (equal in every configuration, or the run fails), the
/// broad phase's own bytes per face, feature pairs with and without ownership; the cost exponent of
/// detection and of whole Engine steps; ratios measured in the same run.

#include "benchkit/experiments.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace glcollide::benchkit {

/// Appends the experiment's runs, tables, summary numbers and notes to `out`. A configuration
/// that cannot run (the BVH before it exists, a list beyond the device) is a failed run, not an
/// exception; bad suites and scenes throw glcollide::Error.
void runBvhExperiment(const Experiment& experiment, ExperimentResult& out, const Progress& progress);

/// How many runs runBvhExperiment() reports progress for (at most).
std::size_t bvhRunCount(const Experiment& experiment);

/// One row of the seed's Tables 1-3 (seeds/001, Kim 2024) exactly as the OCR printed it; several
/// cells are garbled ("012 s", "0.16 vs", "481 ps") and are quoted, not interpreted.
struct SeedTableRow {
    std::uint32_t triangles;
    std::array<const char*, 2> build, refit, traverse; ///< {GPU (ours), CPU}
};
const std::array<SeedTableRow, 3>& seedTables();

} // namespace glcollide::benchkit
