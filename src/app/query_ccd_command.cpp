// glcollide query ccd: answers a CSV of continuous-collision queries (the CCD benchmark's layout)
// on the GPU in one batch with the conservative float CCD (docs/ccd.md, "query ccd").

#include "app/commands.hpp"

#include "cpu/oracle/ccd_query_csv.hpp"
#include "cpu/oracle/ccd_rounding.hpp"
#include "gl/gpu_timer.hpp"
#include "passes/ccd_query_pass.hpp"

#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace glcollide::app {
namespace {

static_assert(kQueryCcdDefaultBudget == passes::kDefaultCcdBudget);
static_assert(kQueryCcdDefaultRounds == passes::kDefaultCcdContinuationRounds);

passes::CcdKind parseKind(const std::string& kind) {
    if (kind == "vf") return passes::CcdKind::VertexFace;
    if (kind == "ee") return passes::CcdKind::EdgeEdge;
    throw Error("--kind: expected vf (vertex-face) or ee (edge-edge), got '" + kind + "'");
}

mpq_class parseMinSeparation(const std::string& text) {
    const std::optional<mpq_class> d = cpu::parseExactDecimal(text);
    if (!d) throw Error("--min-separation: '" + text + "' is not a decimal number");
    if (sgn(*d) < 0) throw Error("--min-separation: " + text + " is negative; expected a distance >= 0");
    return *d;
}

/// The float queries the GPU decides: every coordinate rounded to the nearest float, and the
/// minimum separation widened to cover the rounding (cpu/oracle/ccd_rounding.hpp).
std::vector<passes::CcdQuery> roundedQueries(const std::vector<cpu::CcdCsvQuery>& csv,
                                             const mpq_class& minSeparation, const std::string& file,
                                             std::size_t& widened) {
    std::vector<passes::CcdQuery> queries;
    queries.reserve(csv.size());
    widened = 0;
    for (const cpu::CcdCsvQuery& q : csv) {
        try {
            const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(q.points, minSeparation);
            queries.push_back({r.points, r.minSeparation});
            widened += sgn(r.roundingError) != 0 ? 1 : 0;
        } catch (const Error& e) {
            throw Error(file + ":" + std::to_string(q.lines[0]) +
                        ": this query's minimum separation plus its " + "rounding cover: " + e.what());
        }
    }
    return queries;
}

std::string answerLines(const passes::CcdQueryResult& result, bool withToi) {
    std::ostringstream text;
    char toi[32];
    for (std::size_t i = 0; i < result.mayCollide.size(); ++i) {
        text << (result.mayCollide[i] != 0 ? '1' : '0');
        if (withToi) {
            std::snprintf(toi, sizeof toi, "%.9g", static_cast<double>(result.toi[i])); // round-trips a float
            text << ',' << toi;
        }
        text << '\n';
    }
    return text.str();
}

/// "; against the file's ground truth: F false negatives, P false positives" when every query has
/// one; empty otherwise. The ground truth is read for this line only, never for an answer.
std::string groundTruthSummary(const std::vector<cpu::CcdCsvQuery>& csv,
                               const passes::CcdQueryResult& result) {
    std::size_t falseNegatives = 0, falsePositives = 0;
    for (std::size_t i = 0; i < csv.size(); ++i) {
        if (!csv[i].truth) return "";
        const bool answer = result.mayCollide[i] != 0;
        falseNegatives += *csv[i].truth && !answer ? 1 : 0;
        falsePositives += !*csv[i].truth && answer ? 1 : 0;
    }
    return "; against the file's ground truth: " + std::to_string(falseNegatives) + " false negatives, " +
           std::to_string(falsePositives) + " false positives";
}

} // namespace

int queryCcdCommand(const QueryCcdOptions& options) {
    // Parse and round before creating a context: a bad row fails fast and names its line.
    const passes::CcdKind kind = parseKind(options.kind);
    const mpq_class minSeparation = parseMinSeparation(options.minSeparation);
    if (options.rounds < 0)
        throw Error("--rounds: expected 0 or more, got " + std::to_string(options.rounds));
    if (options.budget < 1)
        throw Error("--budget: expected at least 1 box per query, got " + std::to_string(options.budget));
    const std::vector<cpu::CcdCsvQuery> csv = cpu::readCcdQueryCsv(options.inPath);
    std::size_t widened = 0;
    const std::vector<passes::CcdQuery> queries = roundedQueries(csv, minSeparation, options.inPath, widened);

    HeadlessContext context({options.device});
    const passes::CcdQueryPass pass(options.budget, options.rounds);
    pass.prepare(kind); // compiled (or loaded from the program cache) outside the timing
    // The GPU work timed twice: by the host clock around run() (uploads, dispatches, read-backs) and
    // by GPU timestamps bracketing it.
    gl::GpuTimer timer(1);
    timer.beginFrame();
    timer.begin(0);
    const auto start = std::chrono::steady_clock::now();
    const passes::CcdQueryResult result = pass.run(kind, queries);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timer.end(0);
    const double gpuSeconds = timer.resolveMilliseconds()[0] / 1000.0;

    const std::string text = answerLines(result, options.toi);
    if (options.outPath.empty()) {
        std::cout << text << std::flush;
        return 0;
    }
    std::ofstream out(options.outPath, std::ios::binary);
    if (!out) throw Error(options.outPath + ": cannot open for writing");
    out << text;
    out.close();
    if (!out) throw Error(options.outPath + ": write failed");
    std::size_t hits = 0;
    for (std::uint8_t r : result.mayCollide) hits += r;
    char rate[96];
    std::snprintf(rate, sizeof rate, "%.3f s host clock, %.3f s GPU timestamps, %.0f queries/s", seconds,
                  gpuSeconds, seconds > 0 ? static_cast<double>(queries.size()) / seconds : 0.0);
    std::cout << queries.size() << " queries, " << hits << " may collide, " << result.capped << " capped ("
              << passes::toString(kind) << ", budget " << pass.budget() << ", " << result.continued
              << " continued in up to " << pass.continuationRounds() << " rounds, " << result.boxes
              << " boxes, " << widened << " rounded to float with the separation widened; " << rate << ")"
              << groundTruthSummary(csv, result) << " on " << context.deviceDescription() << " | "
              << context.glInfo().renderer << "\n";
    return 0;
}

} // namespace glcollide::app
