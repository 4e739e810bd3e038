#include "benchkit/report.hpp"

#include "benchkit/svg_plot.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <thread>

namespace glcollide::benchkit {
namespace {

using json = nlohmann::ordered_json;

/// Three significant digits, no exponent for ordinary magnitudes.
std::string num(double v) {
    if (std::isnan(v)) return "n/a";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if (v == std::floor(v) && std::abs(v) < 1e9) return std::to_string(static_cast<long long>(v));
    std::ostringstream s;
    const double a = std::abs(v);
    if (a != 0 && (a < 1e-3 || a >= 1e7))
        s << std::setprecision(3) << std::scientific << v;
    else if (a >= 1000)
        s << std::fixed << std::setprecision(0) << v;
    else
        s << std::setprecision(a >= 100 ? 4 : 3) << v;
    return s.str();
}

/// JSON numbers must be finite; non-finite values (a diverged run) become null.
json finiteOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

std::string slug(const std::string& text) {
    std::string s;
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u))
            s += static_cast<char>(std::tolower(u));
        else if (!s.empty() && s.back() != '-')
            s += '-';
    }
    while (!s.empty() && s.back() == '-') s.pop_back();
    return s.empty() ? "scene" : s;
}

/// The measured (not failed) runs of one configuration, in suite order.
std::vector<RunResult> runsOf(const ExperimentResult& r, const std::string& config) {
    std::vector<RunResult> runs;
    for (const RunResult& run : r.runs)
        if (run.config == config && run.failure.empty()) runs.push_back(run);
    return runs;
}

bool accuracy(const ExperimentResult& r) {
    return r.experiment.kind != ExperimentKind::Scaling;
}

std::vector<std::string> sceneOrder(const ExperimentResult& r) {
    std::vector<std::string> scenes;
    for (const RunResult& run : r.runs)
        if (std::find(scenes.begin(), scenes.end(), run.scene) == scenes.end()) scenes.push_back(run.scene);
    return scenes;
}

/// The metrics worth a table column for each kind (all of them are in the JSON).
std::vector<std::pair<std::string, std::string>> tableMetrics(const Experiment& experiment) {
    switch (experiment.kind) {
    case ExperimentKind::Scaling:
        return {};
    case ExperimentKind::BroadPhase:
        return {{"candidate_pairs", "candidates"},
                {"exact_intersecting_pairs", "exact pairs"},
                {"candidates_missing_intersections", "missed"}};
    case ExperimentKind::NarrowPhase:
        return {{"exact_intersecting_pairs", "exact pairs"},
                {"false_positives", "false pos."},
                {"false_negatives", "false neg."}};
    case ExperimentKind::Integration:
        if (experiment.reference == IntegrationReference::Oscillator)
            return {{"max_position_error_m", "max error (m)"},
                    {"period_error_relative", "period error (rel.)"},
                    {"amplitude_ratio_per_period", "amplitude ratio/period"},
                    {"numerical_damping_per_period", "numerical damping/period"},
                    {"energy_drift_relative", "energy drift (rel.)"},
                    {"gpu_ms_per_simulated_second", "GPU ms/simulated s"},
                    {"wall_ms_per_simulated_second", "wall ms/simulated s"}};
        return {{"max_position_error_m", "max error (m)"},
                {"max_energy_error_relative", "energy error (rel.)"},
                {"energy_drift_relative", "energy drift (rel.)"},
                {"gpu_ms_per_simulated_second", "GPU ms/simulated s"},
                {"wall_ms_per_simulated_second", "wall ms/simulated s"}};
    case ExperimentKind::Contact:
        return {{"deepest_penetration_m", "deepest penetration (m)"},
                {"max_intersecting_pairs", "max intersecting pairs"},
                {"max_contacts", "max contacts"}};
    case ExperimentKind::Bvh:
        return {{"candidate_pairs", "candidates"},
                {"broad_phase_ms", "broad phase ms"},
                {"build_ms", "build"},
                {"refit_ms", "refit"},
                {"traverse_ms", "traverse"},
                {"bbupdate_ms", "BBUpdate"},
                {"bbcollision_ms", "BBCollision"},
                {"feature_pairs_ms", "FeaturePairs"},
                {"broad_phase_bytes_per_face", "bytes/face"},
                {"detection_ms_per_substep", "engine: detection ms/substep"},
                {"dynamics_ms_per_substep", "engine: rest ms/substep"}};
    case ExperimentKind::Ccd:
        return {{"queries", "queries"},
                {"false_negatives", "FN"},
                {"false_positives", "FP"},
                {"positives", "positives"},
                {"capped", "capped"},
                {"queries_per_second_wall", "q/s (wall)"},
                {"queries_per_second_gpu", "q/s (GPU)"},
                {"ours_per_ti_double_qps", "ours/TI double"},
                {"candidate_pairs", "candidates"},
                {"ccd_capped", "CCD capped"}};
    case ExperimentKind::Response:
        return {{"max_intersecting_pairs", "max intersecting pairs"},
                {"energy_start_j", "E start (J)"},
                {"energy_end_j", "E end (J)"},
                {"energy_max_rise_j", "largest rise (J)"},
                {"energy_rise_over_allowance", "rise / allowance"},
                {"safe_step_fraction", "cut substeps"},
                {"safe_step_froze_all", "froze all"},
                {"energy_guard_fraction", "guard acted"},
                {"energy_guard_pull_back_fraction", "pulled back"},
                {"energy_guard_back_to_start_fraction", "back to start"},
                {"solver_iterations_per_substep", "CG it./substep"},
                {"gpu_ms_per_substep", "GPU ms/substep"}};
    }
    return {};
}

struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

Table tableOf(const ExperimentResult& r) {
    Table t;
    t.header = {"scene",        "config", "faces", "substeps/frame", "GPU ms/frame (median [q1, q3])",
                "wall ms/frame"};
    if (accuracy(r))
        t.header.push_back(r.timeLabel);
    else
        t.header.push_back("GPU ms/substep");
    const auto metrics = tableMetrics(r.experiment);
    for (const auto& m : metrics) t.header.push_back(m.second);
    for (const RunResult& run : r.runs) {
        std::vector<std::string> row{run.scene, run.config, run.faces ? num(run.faces) : "-",
                                     num(run.substeps)};
        if (!run.failure.empty()) {
            row.push_back("failed: " + run.failure);
            while (row.size() < t.header.size()) row.emplace_back("-");
        } else {
            row.push_back(num(run.gpuMs.median) + " [" + num(run.gpuMs.q1) + ", " + num(run.gpuMs.q3) + "]");
            row.push_back(run.wallMs.samples ? num(run.wallMs.median) : "-");
            row.push_back(num(run.time));
            for (const auto& m : metrics) row.push_back(num(run.metric(m.first, std::nan(""))));
        }
        t.rows.push_back(std::move(row));
    }
    return t;
}

std::string markdownTable(const Table& t) {
    std::ostringstream s;
    s << "|";
    for (const std::string& h : t.header) s << ' ' << h << " |";
    s << "\n|";
    for (std::size_t i = 0; i < t.header.size(); ++i) s << (i < 2 ? "---|" : "---:|");
    s << "\n";
    for (const auto& row : t.rows) {
        s << "|";
        for (const std::string& cell : row) s << ' ' << cell << " |";
        s << "\n";
    }
    return s.str();
}

/// The experiment's own tables (bvh), as Markdown.
std::string summaryMarkdown(const ExperimentResult& r) {
    std::ostringstream s;
    for (const SummaryTable& t : r.tables) {
        Table table;
        table.header = t.header;
        table.rows = t.rows;
        s << "**" << t.title << "**\n\n" << markdownTable(table) << "\n";
    }
    return s.str();
}

std::string deviceLine(const RunContext& c) {
    return c.renderer + " (" + c.glVersion + (c.softwareRenderer ? "; software rasteriser, not a GPU" : "") +
           "), " + c.eglDevice + ", CPU " + c.cpuModel + ", commit " + c.gitCommit + ", " + c.dateUtc;
}

} // namespace

double logLogSlope(const std::vector<RunResult>& runs) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const RunResult& r : runs) {
        if (!r.failure.empty() || r.faces == 0 || !(r.time > 0) || !std::isfinite(r.time)) continue;
        const double x = std::log(double(r.faces)), y = std::log(r.time);
        n += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    const double d = n * sxx - sx * sx;
    if (n < 2 || d <= 0) return std::nan("");
    return (n * sxy - sx * sy) / d;
}

std::string benchmarkJson(const RunContext& c, const Suite& suite,
                          const std::vector<ExperimentResult>& results) {
    json context = {
        {"date", c.dateUtc},
        {"host_name", ""},
        {"executable", "glcollide bench"},
        {"num_cpus", std::thread::hardware_concurrency()},
        {"mhz_per_cpu", 0},
        {"cpu_scaling_enabled", false},
        {"caches", json::array()},
        {"library_build_type", c.buildType == "Debug" ? "debug" : "release"},
        {"gl_renderer", c.renderer},
        {"gl_renderer_slug", c.rendererSlug},
        {"gl_version", c.glVersion},
        {"gl_vendor", c.glVendor},
        {"gl_software_renderer", c.softwareRenderer ? "true" : "false"},
        {"egl_device", c.eglDevice},
        {"egl_vendor", c.eglVendor},
        {"egl_version", c.eglVersion},
        {"cpu_model", c.cpuModel},
        {"git_commit", c.gitCommit},
        {"glcollide_build_type", c.buildType},
        {"date_utc", c.dateUtc},
        {"suite", suite.name},
        {"suite_source", suite.source},
        {"timing",
         "GPU ms per frame from GL_TIMESTAMP pairs around each pass (summed over the frame's substeps); "
         "median over the measured frames, spread as quartiles and range; wall = CPU time of Engine::step()"},
    };
    json benchmarks = json::array();
    int family = 0;
    for (const ExperimentResult& r : results)
        for (const RunResult& run : r.runs) {
            const std::string base = r.experiment.name + "/" + run.scene + "/" + run.config;
            auto entry = [&](const std::string& pass, const Summary& s, int instance) {
                json e = {{"name", base + "/" + pass},
                          {"family_index", family},
                          {"per_family_instance_index", instance},
                          {"run_name", base + "/" + pass},
                          {"run_type", "iteration"},
                          {"repetitions", 1},
                          {"repetition_index", 0},
                          {"threads", 1},
                          {"iterations", s.samples},
                          {"real_time", finiteOrNull(s.median)},
                          {"cpu_time", finiteOrNull(s.median)},
                          {"time_unit", "ms"},
                          {"experiment", r.experiment.name},
                          {"kind", kindName(r.experiment.kind)},
                          {"scene", run.scene},
                          {"config", run.config},
                          {"pass", pass},
                          {"min", finiteOrNull(s.min)},
                          {"max", finiteOrNull(s.max)},
                          {"q1", finiteOrNull(s.q1)},
                          {"q3", finiteOrNull(s.q3)},
                          {"nodes", run.nodes},
                          {"springs", run.springs},
                          {"faces", run.faces},
                          {"substeps_per_frame", run.substeps}};
                if (!run.failure.empty()) e["error_occurred"] = true, e["error_message"] = run.failure;
                if (accuracy(r) && pass == "gpu_total") {
                    e["accuracy_time"] = finiteOrNull(run.time);
                    e["accuracy_time_label"] = r.timeLabel;
                    e["accuracy_error"] = finiteOrNull(run.error);
                    e["accuracy_error_label"] = r.errorLabel;
                }
                for (const Metric& m : run.metrics) e[m.key] = finiteOrNull(m.value);
                benchmarks.push_back(std::move(e));
            };
            int instance = 0;
            for (std::size_t p = 0; p < run.passNames.size() && p < run.passMs.size(); ++p)
                entry(run.passNames[p], run.passMs[p], instance++);
            entry("gpu_total", run.gpuMs, instance++);
            if (run.wallMs.samples) entry("wall", run.wallMs, instance++);
            ++family;
        }
    // Experiment-level numbers and tables (the bvh experiment's slopes, ratios, seed tables);
    // compare.py reads only `benchmarks` and ignores this.
    json summaries = json::array();
    for (const ExperimentResult& r : results) {
        if (r.summary.empty() && r.tables.empty()) continue;
        json metrics = json::object();
        for (const Metric& m : r.summary) metrics[m.key] = finiteOrNull(m.value);
        json tables = json::array();
        for (const SummaryTable& t : r.tables)
            tables.push_back({{"title", t.title}, {"header", t.header}, {"rows", t.rows}});
        summaries.push_back({{"experiment", r.experiment.name},
                             {"kind", kindName(r.experiment.kind)},
                             {"metrics", metrics},
                             {"tables", tables},
                             {"notes", r.notes}});
    }
    return json{{"context", context}, {"benchmarks", benchmarks}, {"experiment_summaries", summaries}}.dump(
               2) +
           "\n";
}

std::string textTable(const ExperimentResult& r) {
    const Table t = tableOf(r);
    std::vector<std::size_t> width(t.header.size(), 0);
    for (std::size_t i = 0; i < t.header.size(); ++i) width[i] = t.header[i].size();
    for (const auto& row : t.rows)
        for (std::size_t i = 0; i < row.size() && i < width.size(); ++i)
            width[i] = std::max(width[i], row[i].size());
    std::ostringstream s;
    s << "== " << r.experiment.name << ": " << r.experiment.title << "\n";
    auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t i = 0; i < cells.size() && i < width.size(); ++i)
            s << (i ? "  " : "") << (i < 2 ? std::left : std::right) << std::setw(static_cast<int>(width[i]))
              << cells[i];
        s << std::right << "\n";
    };
    line(t.header);
    for (const auto& row : t.rows) line(row);
    for (const SummaryTable& table : r.tables) {
        std::vector<std::size_t> w(table.header.size(), 0);
        for (std::size_t i = 0; i < w.size(); ++i) w[i] = table.header[i].size();
        for (const auto& row : table.rows)
            for (std::size_t i = 0; i < row.size() && i < w.size(); ++i) w[i] = std::max(w[i], row[i].size());
        s << "-- " << table.title << "\n";
        const auto put = [&](const std::vector<std::string>& cells) {
            for (std::size_t i = 0; i < cells.size() && i < w.size(); ++i)
                s << (i ? "  " : "") << (i == 0 ? std::left : std::right) << std::setw(static_cast<int>(w[i]))
                  << cells[i];
            s << std::right << "\n";
        };
        put(table.header);
        for (const auto& row : table.rows) put(row);
    }
    if (r.experiment.kind == ExperimentKind::Scaling)
        for (const ConfigEntry& c : r.experiment.configs) {
            s << "   " << c.name << ": GPU time per substep grows as faces^"
              << num(logLogSlope(runsOf(r, c.name))) << "\n";
        }
    for (const std::string& note : r.notes) s << "   note: " << note << "\n";
    return s.str();
}

std::vector<PlotFile> plots(const ExperimentResult& r) {
    std::vector<PlotFile> files;
    if (r.experiment.kind == ExperimentKind::Bvh) {
        // Time per detection (engine rows: per substep) against faces on the generated cloths.
        PlotSpec spec;
        spec.title = r.experiment.title;
        spec.xLabel = "faces";
        spec.yLabel = "GPU ms per detection / per engine substep";
        spec.logX = spec.logY = true;
        std::vector<std::string> configs;
        for (const RunResult& run : r.runs)
            if (run.metric("generated") == 1 &&
                std::find(configs.begin(), configs.end(), run.config) == configs.end())
                configs.push_back(run.config);
        for (const std::string& config : configs) {
            PlotSeries series;
            std::vector<RunResult> runs;
            for (const RunResult& run : r.runs)
                if (run.config == config && run.failure.empty() && run.metric("generated") == 1 &&
                    run.time > 0) {
                    runs.push_back(run);
                    series.points.push_back({double(run.faces), run.time, ""});
                }
            if (series.points.empty()) continue;
            series.name = config + " (slope " + num(logLogSlope(runs)) + ")";
            std::sort(series.points.begin(), series.points.end(),
                      [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
            spec.series.push_back(std::move(series));
        }
        if (!spec.series.empty()) files.push_back({r.experiment.name + ".svg", spec.title, renderSvg(spec)});
        return files;
    }
    if (!accuracy(r)) {
        PlotSpec spec;
        spec.title = r.experiment.title;
        spec.xLabel = "faces";
        spec.yLabel = "GPU ms per substep";
        spec.logX = spec.logY = true;
        for (const ConfigEntry& c : r.experiment.configs) {
            PlotSeries series;
            const std::vector<RunResult> runs = runsOf(r, c.name);
            for (const RunResult& run : runs)
                series.points.push_back({double(run.faces), run.time, run.scene});
            series.name = c.name + " (slope " + num(logLogSlope(runs)) + ")";
            std::sort(series.points.begin(), series.points.end(),
                      [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
            spec.series.push_back(std::move(series));
        }
        files.push_back({r.experiment.name + ".svg", spec.title, renderSvg(spec)});
        return files;
    }
    for (const std::string& scene : sceneOrder(r)) {
        PlotSpec spec;
        spec.title = r.experiment.name + ": " + scene; // the long title is in the report next to it
        spec.xLabel = r.timeLabel;
        spec.yLabel = r.errorLabel;
        spec.logX = true;
        spec.logY = true;
        spec.paretoFront = true;
        PlotSeries series;
        series.name = "configurations";
        series.connect = false;
        series.labelAll = false; // labels of every point collide; the front is labelled, the table has all
        for (const RunResult& run : r.runs)
            if (run.scene == scene && run.failure.empty())
                series.points.push_back({run.time, run.error, run.config});
        spec.series.push_back(std::move(series));
        files.push_back({r.experiment.name + "-" + slug(scene) + ".svg", spec.title, renderSvg(spec)});
    }
    return files;
}

std::string markdownReport(const RunContext& c, const Suite& suite,
                           const std::vector<ExperimentResult>& results,
                           const std::vector<std::vector<PlotFile>>& plotFiles) {
    std::ostringstream s;
    s << "## " << c.renderer << "\n\n";
    s << "Device: " << deviceLine(c) << ". Suite: `" << suite.name << "` (" << suite.source << ").";
    if (c.softwareRenderer) s << " **These are llvmpipe (CPU) timings, not GPU timings.**";
    s << "\n\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const ExperimentResult& r = results[i];
        s << "### " << r.experiment.title << " (`" << r.experiment.name << "`, "
          << kindName(r.experiment.kind) << ")\n\n";
        s << r.experiment.warmupFrames << " warm-up and " << r.experiment.frames
          << " measured frames per run.";
        if (r.experiment.kind == ExperimentKind::Bvh)
            s << " Plotted: GPU ms per detection against faces on the folded cloths, log-log.";
        else if (accuracy(r))
            s << " Plotted: " << r.timeLabel << " against " << r.errorLabel << ".";
        s << "\n\n";
        for (const std::string& note : r.notes) s << "- " << note << "\n";
        if (r.experiment.kind == ExperimentKind::Scaling)
            for (const ConfigEntry& cfg : r.experiment.configs) {
                s << "- " << cfg.name << ": GPU time per substep grows as faces^"
                  << num(logLogSlope(runsOf(r, cfg.name))) << "\n";
            }
        s << "\n" << markdownTable(tableOf(r)) << "\n" << summaryMarkdown(r);
        if (i < plotFiles.size())
            for (const PlotFile& f : plotFiles[i]) s << "![" << f.title << "](" << f.name << ")\n";
        s << "\n";
    }
    return s.str();
}

std::string headlineTable(const RunContext& c, const std::vector<ExperimentResult>& results) {
    std::ostringstream s;
    s << "Measured on " << c.renderer
      << (c.softwareRenderer ? " (software rasteriser on the CPU, not a GPU)" : "") << ", commit "
      << c.gitCommit << ", " << c.dateUtc.substr(0, 10) << ".\n\n";
    s << "| experiment | scene | fastest: config (time, error) | least error: config (time, error) |\n";
    s << "|---|---|---|---|\n";
    for (const ExperimentResult& r : results) {
        if (!accuracy(r) || r.experiment.kind == ExperimentKind::Bvh) continue;
        const bool ccd = r.experiment.kind == ExperimentKind::Ccd; // its sweeps and workloads have own tables
        // Triangle-pair families are summed into one row per configuration: one line for all of them.
        std::vector<std::string> scenes;
        std::map<std::string, std::map<std::string, std::pair<double, double>>>
            points; // scene -> config -> (time, error)
        for (const RunResult& run : r.runs) {
            if (!run.failure.empty()) continue;
            if (ccd && (run.metric("sweep") == 1 || run.metric("engine_workload") == 1)) continue;
            const bool family = run.scene.rfind("pairs: ", 0) == 0;
            const std::string scene = family ? "all triangle-pair families (sum)" : run.scene;
            if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
            auto& p = points[scene][run.config];
            p.first += run.time;
            p.second += run.error;
        }
        for (const std::string& scene : scenes) {
            const auto& configs = points[scene];
            auto fastest = configs.begin(), best = configs.begin();
            for (auto it = configs.begin(); it != configs.end(); ++it) {
                if (it->second.first < fastest->second.first) fastest = it;
                if (it->second.second < best->second.second ||
                    (it->second.second == best->second.second && it->second.first < best->second.first))
                    best = it;
            }
            const auto cell = [&](const auto& it) {
                return it->first + " (" + num(it->second.first) + ", " + num(it->second.second) + ")";
            };
            s << "| " << r.experiment.title << " | " << scene << " | " << cell(fastest) << " | " << cell(best)
              << " |\n";
        }
    }
    for (const ExperimentResult& r : results) {
        if (accuracy(r)) continue;
        for (const ConfigEntry& cfg : r.experiment.configs) {
            const std::vector<RunResult> runs = runsOf(r, cfg.name);
            double largest = 0, ms = 0;
            for (const RunResult& run : runs)
                if (run.faces > largest) largest = run.faces, ms = run.time;
            s << "| " << r.experiment.title << " | " << cfg.name << " | cost per substep grows as faces^"
              << num(logLogSlope(runs)) << " | " << num(ms) << " ms per substep at " << num(largest)
              << " faces |\n";
        }
    }
    for (const ExperimentResult& r : results) {
        if (r.experiment.kind != ExperimentKind::Bvh) continue;
        for (const Metric& m : r.summary) {
            if (m.key.rfind("slope_detection/", 0) != 0) continue;
            const std::string config = m.key.substr(16);
            double largest = 0, ms = 0; // the largest scaling cloth this configuration ran on
            for (const RunResult& run : r.runs)
                if (run.config == config && run.failure.empty() && run.metric("in_scaling") == 1 &&
                    run.faces > largest)
                    largest = run.faces, ms = run.time;
            s << "| " << r.experiment.title << " | " << config << " | detection per substep grows as faces^"
              << num(m.value) << " | " << num(ms) << " ms per detection at " << num(largest)
              << " faces (folded cloth) |\n";
        }
    }
    std::string units;
    for (const ExperimentResult& r : results)
        if (accuracy(r) && r.experiment.kind != ExperimentKind::Bvh)
            units +=
                (units.empty() ? "" : "; ") + r.experiment.name + ": " + r.timeLabel + ", " + r.errorLabel;
    if (!units.empty()) s << "\nTimes and errors in each experiment's units: " << units << ".\n";
    return s.str();
}

} // namespace glcollide::benchkit
