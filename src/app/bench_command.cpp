// glcollide bench: runs a benchmark suite headless and writes Google Benchmark JSON, SVG plots
// and a Markdown report; the table goes to stdout, progress to stderr (docs/benchmarks.md).

#include "app/commands.hpp"
#include "app/self_check_report.hpp"

#include "benchkit/experiments.hpp"
#include "benchkit/report.hpp"
#include "benchkit/run_context.hpp"
#include "benchkit/suite.hpp"

#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace glcollide::app {
namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path.string() + ": cannot open for writing");
    out << text;
    out.close();
    if (!out) throw Error(path.string() + ": write failed");
}

benchkit::Suite chooseSuite(const BenchOptions& options) {
    if (options.suite.empty() || options.suite == "default") return benchkit::defaultSuite();
    if (options.suite == "smoke") return benchkit::smokeSuite();
    return benchkit::loadSuite(options.suite);
}

/// Keeps the experiments named by --only (each name must exist) and applies --frames.
void select(benchkit::Suite& suite, const BenchOptions& options) {
    if (!options.only.empty()) {
        for (const std::string& name : options.only)
            if (std::none_of(suite.experiments.begin(), suite.experiments.end(),
                             [&](const benchkit::Experiment& e) { return e.name == name; })) {
                std::string names;
                for (const benchkit::Experiment& e : suite.experiments)
                    names += (names.empty() ? "" : ", ") + e.name;
                throw Error("--only " + name + ": no such experiment in " + suite.source +
                            " (it has: " + names + ")");
            }
        std::erase_if(suite.experiments, [&](const benchkit::Experiment& e) {
            return std::find(options.only.begin(), options.only.end(), e.name) == options.only.end();
        });
    }
    if (options.frames)
        for (benchkit::Experiment& e : suite.experiments) e.frames = *options.frames;
}

fs::path outputDir(const std::string& pattern, const std::string& slug) {
    std::string dir = pattern;
    for (std::size_t at; (at = dir.find("{device}")) != std::string::npos;) dir.replace(at, 8, slug);
    return dir;
}

} // namespace

int benchCommand(const BenchOptions& options) {
    benchkit::Suite suite = chooseSuite(options); // parse first: a bad suite fails before any GL work
    select(suite, options);
    HeadlessContext context({.device = options.device});
    const benchkit::RunContext run = benchkit::describeRun(context);
    const fs::path out = outputDir(options.outDir, run.rendererSlug);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw Error(out.string() + ": cannot create the output folder: " + ec.message());

    const auto log = [&](const std::string& line) {
        if (!options.quiet) std::cerr << "glcollide bench: " << line << "\n";
    };
    log("suite " + suite.name + " (" + std::to_string(suite.experiments.size()) + " experiments) on " +
        run.renderer + ", " + run.eglDevice + ", commit " + run.gitCommit);
    // The suite measures robust precision against the oracle; first make sure this device computes
    // it exactly on the built-in hard cases (once per device, driver and shader).
    log("robust self-check: " + selfCheckLine(checkRobustBeforeUse()));
    if (run.softwareRenderer)
        log("software renderer: these timings are CPU (llvmpipe) timings, not GPU timings");

    const auto start = std::chrono::steady_clock::now();
    std::vector<benchkit::ExperimentResult> results;
    std::vector<std::vector<benchkit::PlotFile>> plots;
    std::size_t failed = 0;
    for (const benchkit::Experiment& experiment : suite.experiments) {
        results.push_back(benchkit::runExperiment(experiment, log));
        for (const benchkit::RunResult& r : results.back().runs) failed += r.failure.empty() ? 0 : 1;
        std::cout << benchkit::textTable(results.back()) << "\n" << std::flush;
        plots.push_back(benchkit::plots(results.back()));
        for (const benchkit::PlotFile& p : plots.back()) writeText(out / p.name, p.svg);
        // Rewritten after every experiment: an interrupted run keeps what it measured.
        writeText(out / "bench.json", benchkit::benchmarkJson(run, suite, results));
    }
    writeText(out / "bench.json", benchkit::benchmarkJson(run, suite, results));
    writeText(out / "report.md", benchkit::markdownReport(run, suite, results, plots));
    writeText(out / "headline.md", benchkit::headlineTable(run, results));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log("wrote " + (out / "bench.json").string() + ", report.md, headline.md and the SVG plots (" +
        std::to_string(static_cast<int>(std::lround(seconds))) + " s)");
    if (failed) log(std::to_string(failed) + " run(s) could not be measured: see the 'failed' rows");
    return 0;
}

} // namespace glcollide::app
