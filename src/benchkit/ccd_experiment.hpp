#pragma once
/// \file The `ccd` experiment (docs/benchmarks.md, "The ccd experiment"): the conservative float
/// CCD of `glcollide query ccd` (passes::CcdQueryPass) on query sets with ground truth
/// (Sample-Queries, cloth-funnel, cloth-ball 92 -> 93): false negatives, false positives, capped
/// queries and queries per second; what accuracy costs (budget and minimum-separation sweeps, 2^k
/// scaling); Tight-Inclusion on one core of the same machine in the same run when its driver is
/// built (bench/peers/tight-inclusion); and swept against discrete detection of whole steps as an
/// engine workload (passes::CollisionDetection).

#include "benchkit/experiments.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace glcollide::benchkit {

/// Appends the experiment's runs, tables and notes to `out`. A missing peer is a note; bad data
/// files throw glcollide::Error.
void runCcdExperiment(const Experiment& experiment, ExperimentResult& out, const Progress& progress);

/// How many runs runCcdExperiment() reports progress for (at most).
std::size_t ccdRunCount(const Experiment& experiment);

/// Answers against ground truth: a false negative is a colliding query answered "no collision",
/// a false positive a free one answered "may collide".
struct CcdTally {
    std::size_t queries = 0, truthPositives = 0, positives = 0, falseNegatives = 0, falsePositives = 0;
};

/// Counts `answers` (non-zero: may collide) against `truth`, query by query. Throws
/// glcollide::Error when the two differ in length.
CcdTally tallyCcd(const std::vector<std::uint8_t>& answers, const std::vector<bool>& truth);

} // namespace glcollide::benchkit
