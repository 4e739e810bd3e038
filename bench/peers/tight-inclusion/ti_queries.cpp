// ti_queries: runs Tight-Inclusion's CCD (linked in by build.sh, never by glcollide's build) on
// query files in the CCD benchmark's CSV layout and prints one JSON object: queries, positives,
// false negatives and false positives against the truth column, time, queries per second, and
// the settings used. Our code; Tight-Inclusion is MIT-licensed (its LICENSE is copied next to the
// binaries by build.sh).
//
//   ti_queries_double --kind vf|ee [--set NAME] FILE.csv...
//   ti_queries_float  --kind vf|ee [--set NAME] FILE.csv...
//     --set: a name for the files together, copied into the output ("set").
//
// Input: 8 rows per query, each row x, y, z as numerator,denominator integer pairs (any size),
// optionally a 7th column, the ground truth (0 or 1); every row of a file has the same number of
// columns. Rows 1-4: the points at t = 0, rows 5-8: at t = 1 (vertex-face: the vertex, then the
// triangle; edge-edge: edge A, then edge B). Each rational is rounded to the nearest double (ties
// to even); the float build then casts the doubles to float inside TI's double-input entry points
// (TIGHT_INCLUSION_FLOAT_WITH_DOUBLE_INPUT), which is what TI's own benchmark (app/main.cpp) does.
// Bad input: "ti_queries: error: FILE:LINE: what", exit 1.
//
// Settings: those of TI's benchmark, app/main.cpp check_all_sample_queries (named in the output):
// minimum separation 0, tolerance 1e-6, max_itr 1e6, t_max 1, err = (-1, -1, -1) (TI computes its
// numerical filter per query), no_zero_toi false, breadth-first search.
// Time: the CCD calls only (parsing and rounding excluded), wall clock of the loop over all
// queries, as TI's benchmark sums the time of each call; and the process's CPU time over the same
// loop (cpu_seconds), which a machine shared with other jobs disturbs less.

#include <tight_inclusion/ccd.hpp>

#include <Eigen/Core>
#include <gmpxx.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <time.h> // clock_gettime, CLOCK_PROCESS_CPUTIME_ID (POSIX)

#ifndef TI_QUERIES_PRECISION
#error "build.sh defines TI_QUERIES_PRECISION (\"double\" or \"float\")"
#endif

namespace {

struct Query {
    std::array<Eigen::Vector3d, 8> points;
    int truth = -1; // -1: the file has no truth column
};

/// The double nearest to q (ties to even). mpq get_d truncates toward zero, so the nearest is that
/// value or its neighbour away from zero; both are compared with q exactly.
double nearestDouble(const mpq_class& q, const std::string& where) {
    const double toward = q.get_d();
    if (!std::isfinite(toward)) throw std::runtime_error(where + ": coordinate outside the double range");
    if (mpq_class(toward) == q) return toward;
    const double away = std::nextafter(toward, sgn(q) > 0 ? INFINITY : -INFINITY);
    if (!std::isfinite(away)) throw std::runtime_error(where + ": coordinate outside the double range");
    const mpq_class dToward = abs(q - mpq_class(toward)), dAway = abs(q - mpq_class(away));
    if (dToward != dAway) return dToward < dAway ? toward : away;
    std::uint64_t bits;
    std::memcpy(&bits, &toward, sizeof bits);
    return (bits & 1u) == 0 ? toward : away;
}

std::vector<Query> readQueries(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<Query> queries;
    std::string line;
    int lineNumber = 0;
    std::size_t columns = 0;
    auto fail = [&](const std::string& why) {
        throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": " + why);
    };
    while (std::getline(in, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::vector<mpz_class> fields;
        std::stringstream row(line);
        std::string field;
        while (std::getline(row, field, ',')) {
            mpz_class value;
            if (field.find_first_not_of(" \t") == std::string::npos || value.set_str(field, 10) != 0)
                fail("not an integer: '" + field + "'");
            fields.push_back(value);
        }
        if (fields.size() != 6 && fields.size() != 7)
            fail("expected 6 or 7 fields, found " + std::to_string(fields.size()));
        if (lineNumber == 1) columns = fields.size();
        if (fields.size() != columns)
            fail("expected " + std::to_string(columns) + " fields as in line 1, found " +
                 std::to_string(fields.size()));
        const int row8 = (lineNumber - 1) % 8;
        const int truth = columns == 7 ? (fields[6] != 0) : -1;
        if (columns == 7 && fields[6] != 0 && fields[6] != 1) fail("the truth column must be 0 or 1");
        if (row8 == 0)
            queries.push_back({{}, truth});
        else if (truth != queries.back().truth)
            fail("ground truth differs within a query");
        for (int k = 0; k < 3; ++k) {
            if (sgn(fields[2 * k + 1]) == 0) fail("zero denominator");
            mpq_class value(fields[2 * k], fields[2 * k + 1]);
            value.canonicalize();
            queries.back().points[row8][k] = nearestDouble(value, path + ":" + std::to_string(lineNumber));
        }
    }
    if (lineNumber % 8 != 0) fail("the file does not end with a whole query (8 rows)");
    return queries;
}

// TI's benchmark settings (app/main.cpp, check_all_sample_queries and check_sample_queries).
constexpr double kMinimumSeparation = 0.0;
constexpr double kTolerance = 1e-6;
constexpr long kMaxIterations = 1000000;
constexpr double kTMax = 1.0;
constexpr bool kNoZeroToi = false;

bool runTi(bool edgeEdge, const Query& q) {
    const Eigen::Array3d err(-1, -1, -1);
    double toi = 0, outputTolerance = kTolerance;
    const auto& v = q.points;
    if (edgeEdge)
        return ticcd::edgeEdgeCCD(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], err, kMinimumSeparation,
                                  toi, kTolerance, kTMax, kMaxIterations, outputTolerance, kNoZeroToi,
                                  ticcd::CCDRootFindingMethod::BREADTH_FIRST_SEARCH);
    return ticcd::vertexFaceCCD(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], err, kMinimumSeparation, toi,
                                kTolerance, kTMax, kMaxIterations, outputTolerance, kNoZeroToi,
                                ticcd::CCDRootFindingMethod::BREADTH_FIRST_SEARCH);
}

/// CPU time of this process, in seconds: on a machine shared with other jobs it counts only the
/// time this process ran, where the wall clock also counts the time it waited for a core.
double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

} // namespace

int main(int argc, char** argv) {
    std::string kind, setName;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--kind" && i + 1 < argc)
            kind = argv[++i];
        else if (arg == "--set" && i + 1 < argc)
            setName = argv[++i];
        else
            files.push_back(arg);
    }
    const bool plainName = setName.find_first_of("\"\\") == std::string::npos;
    if ((kind != "vf" && kind != "ee") || files.empty() || !plainName) {
        std::fprintf(stderr, "usage: %s --kind vf|ee [--set NAME (no quotes or backslashes)] FILE.csv...\n",
                     argv[0]);
        return 2;
    }
    std::vector<Query> queries;
    try {
        for (const std::string& f : files)
            for (Query& q : readQueries(f)) queries.push_back(q);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ti_queries: error: %s\n", e.what());
        return 1;
    }
    const bool edgeEdge = kind == "ee";
    std::vector<char> answers(queries.size());
    const double cpuBegin = cpuSeconds();
    const auto begin = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < queries.size(); ++i) answers[i] = runTi(edgeEdge, queries[i]);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    const double cpu = cpuSeconds() - cpuBegin;

    long positives = 0, truths = 0, falseNegatives = 0, falsePositives = 0;
    bool haveTruth = true;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        positives += answers[i];
        if (queries[i].truth < 0) {
            haveTruth = false;
            continue;
        }
        truths += queries[i].truth;
        falseNegatives += queries[i].truth == 1 && !answers[i];
        falsePositives += queries[i].truth == 0 && answers[i];
    }
    auto orNull = [&](long v) { return haveTruth ? std::to_string(v) : std::string("null"); };
    std::printf(
        "{\"peer\": \"tight-inclusion\", \"set\": \"%s\", \"precision\": \"%s\", \"kind\": \"%s\", "
        "\"files\": %zu, "
        "\"queries\": %zu, \"positives\": %ld, \"truth_positives\": %s, \"false_negatives\": %s, "
        "\"false_positives\": %s, \"seconds\": %.6f, \"queries_per_second\": %.1f, \"cpu_seconds\": %.6f, "
        "\"queries_per_cpu_second\": %.1f, "
        "\"settings\": {\"minimum_separation\": %g, \"tolerance\": %g, \"max_iterations\": %ld, "
        "\"t_max\": %g, \"err\": [-1, -1, -1], \"no_zero_toi\": %s, \"method\": \"breadth-first\", "
        "\"input\": \"rationals rounded to nearest double%s\"}}\n",
        setName.c_str(), TI_QUERIES_PRECISION, kind.c_str(), files.size(), queries.size(), positives,
        orNull(truths).c_str(), orNull(falseNegatives).c_str(), orNull(falsePositives).c_str(), seconds,
        seconds > 0 ? static_cast<double>(queries.size()) / seconds : 0.0, cpu,
        cpu > 0 ? static_cast<double>(queries.size()) / cpu : 0.0, kMinimumSeparation, kTolerance,
        kMaxIterations, kTMax, kNoZeroToi ? "true" : "false",
        std::strcmp(TI_QUERIES_PRECISION, "float") == 0 ? ", then cast to float by TI" : "");
    return 0;
}
