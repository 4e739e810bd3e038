#pragma once
/// \file What `glcollide bench` measured: per run (one scene under one configuration) the
/// per-pass GPU time, wall time, sizes, counts and the errors against ground truth.

#include "benchkit/suite.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::benchkit {

/// Order statistics of one series of samples (ms). The spread is [q1, q3] and [min, max].
struct Summary {
    double median = 0.0, min = 0.0, max = 0.0, q1 = 0.0, q3 = 0.0;
    std::size_t samples = 0;
};

/// Median, quartiles (linear interpolation between order statistics) and range; all 0 for none.
Summary summarize(std::vector<double> samples);

/// A named number: a count ("candidate_pairs"), a size or an error ("false_negatives").
struct Metric {
    std::string key;
    double value = 0.0;
};

struct RunResult {
    std::string scene;
    std::string config;
    std::uint32_t nodes = 0, springs = 0, faces = 0;
    int substeps = 0; ///< per frame
    int frames = 0;   ///< measured frames (the samples of every Summary)
    std::vector<std::string> passNames;
    std::vector<Summary> passMs; ///< GPU ms per frame, one per pass (timestamp queries)
    Summary gpuMs;               ///< sum of the passes, per frame
    Summary wallMs;              ///< CPU wall time of Engine::step(), per frame
    std::vector<Metric> metrics;
    double time = 0.0;   ///< the x of the experiment's plot (see ExperimentResult::timeLabel)
    double error = 0.0;  ///< the y of the experiment's plot (see ExperimentResult::errorLabel)
    std::string failure; ///< non-empty when the run could not be measured (the reason)

    [[nodiscard]] double metric(const std::string& key, double fallback = 0.0) const;
    void set(const std::string& key, double value);
};

/// A table of an experiment's own layout (the bvh experiment's seed tables, slopes, ratios),
/// printed after the run table and kept in the JSON's `experiment_summaries`.
struct SummaryTable {
    std::string title;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

struct ExperimentResult {
    Experiment experiment;
    std::string timeLabel;  ///< "collision GPU ms per substep", ...
    std::string errorLabel; ///< "missed intersecting pairs", ...
    bool errorIsCount = false;
    std::vector<RunResult> runs;
    std::vector<std::string> notes;   ///< what a reader must know (reference used, what is not measured)
    std::vector<SummaryTable> tables; ///< experiment-level tables (bvh)
    std::vector<Metric> summary;      ///< experiment-level numbers (bvh: slopes, ratios, bytes per face)
};

} // namespace glcollide::benchkit
