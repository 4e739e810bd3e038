#pragma once
/// \file The outputs of `glcollide bench`: Google Benchmark JSON, a text table, SVG plots and a
/// Markdown report section, all from the same results.

#include "benchkit/results.hpp"
#include "benchkit/run_context.hpp"
#include "benchkit/suite.hpp"

#include <string>
#include <vector>

namespace glcollide::benchkit {

/// Google Benchmark's JSON schema: `context` (renderer, driver, EGL device, commit, date, ...)
/// and `benchmarks`, one entry per experiment x scene x configuration x pass (plus "gpu_total"
/// and "wall"), named "experiment/scene/config/pass", time in ms (median over the measured
/// frames), the spread and every metric as extra numeric fields. compare.py reads it.
std::string benchmarkJson(const RunContext& context, const Suite& suite,
                          const std::vector<ExperimentResult>& results);

/// The human-readable table of one experiment (stdout).
std::string textTable(const ExperimentResult& result);

/// An SVG file: its name (no directory) and content.
struct PlotFile {
    std::string name;
    std::string title;
    std::string svg;
};

/// Accuracy experiments: time against error per scene, the Pareto front labelled; scaling: GPU
/// time per substep against faces on log-log axes, one line per configuration (pipeline).
std::vector<PlotFile> plots(const ExperimentResult& result);

/// A Markdown section for docs/benchmarks.md: the device, then per experiment its notes, its
/// table and its plots (linked relative to the report's folder).
std::string markdownReport(const RunContext& context, const Suite& suite,
                           const std::vector<ExperimentResult>& results,
                           const std::vector<std::vector<PlotFile>>& plotFiles);

/// The README's headline table: per accuracy experiment and scene the fastest configuration and
/// the fastest one without error; per scaling configuration the log-log slope.
std::string headlineTable(const RunContext& context, const std::vector<ExperimentResult>& results);

/// Least-squares slope of log(time) against log(faces) (the exponent of the cost's growth);
/// NaN with fewer than two usable points.
double logLogSlope(const std::vector<RunResult>& runs);

} // namespace glcollide::benchkit
