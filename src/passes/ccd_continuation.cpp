#include "passes/ccd_continuation.hpp"

#include "core/ccd_cover.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glcollide::passes {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The sum of two doubles and its rounding error: s + err == a + b exactly (Knuth's TwoSum; exact
/// under round-to-nearest whatever the magnitudes, and it has no product a compiler could contract).
struct ExactSum {
    double s, err;
};
ExactSum twoSum(double a, double b) {
    const double s = a + b;
    const double bv = s - a;
    return {s, (a - (s - bv)) + (b - bv)};
}

/// The float nearest the midpoint of a and b, and an upper bound of its distance to it.
struct RoundedMidpoint {
    float value;
    double error;
};
RoundedMidpoint midpoint(float a, float b) {
    const ExactSum sum = twoSum(a, b);               // floats are exact in double; their sum s + err
    const double m = 0.5 * sum.s;                    // exact: s is 0 or at least 2^-149
    const float value = static_cast<float>(m);       // |m| <= max(|a|, |b|): finite
    const double off = std::fabs(m - double(value)); // exact: m and value are within one float ulp
    const double half = 0.5 * std::fabs(sum.err);    // exact: err is a multiple of 2^-149
    // The true midpoint is m + err / 2; their sum rounds at most once: one step up covers it.
    const double error = off == 0.0 || half == 0.0 ? off + half : std::nextafter(off + half, kInfinity);
    return {value, error};
}

/// The least float >= x (x >= 0); infinity when there is none.
float floatAtLeast(double x) {
    float f = static_cast<float>(x);
    if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

/// The largest float <= start + toi * length, for start and length dyadic (the piece's interval).
float globalTime(double start, double length, float toi) {
    const double x = double(toi) * length; // exact: length is a power of two
    const ExactSum t = twoSum(start, x);   // t.s + t.err == start + x
    float f = static_cast<float>(t.s);
    if (double(f) - t.s > t.err) f = std::nextafter(f, -std::numeric_limits<float>::infinity()); // f > exact
    return f;
}

float largestMagnitude(const std::array<glm::vec3, 8>& points) {
    float largest = 0.0f;
    for (const glm::vec3& p : points)
        largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return largest;
}

/// A part [start, start + length] of a query's interval, posed as a float query on [0, 1].
struct Piece {
    double start = 0.0, length = 1.0;
    CcdQuery query;
    CcdAnswer answer;
};

/// The pieces of a query, in time order, that may still change its answer: those before its first
/// piece that may collide without being capped.
template <typename Visit> void openPieces(std::vector<Piece>& pieces, Visit visit) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        if (pieces[i].answer.mayCollide && !pieces[i].answer.capped) return;
        visit(i);
    }
}

} // namespace

std::optional<CcdQuery> halfOfTime(const CcdQuery& query, int half) {
    std::array<glm::vec3, 4> middle;
    double error = 0.0;
    for (std::size_t p = 0; p < 4; ++p)
        for (int k = 0; k < 3; ++k) {
            const RoundedMidpoint m = midpoint(query.points[p][k], query.points[p + 4][k]);
            middle[p][k] = m.value;
            error = std::max(error, m.error);
        }
    CcdQuery piece;
    for (std::size_t p = 0; p < 4; ++p) {
        piece.points[p] = half == 0 ? query.points[p] : middle[p];
        piece.points[p + 4] = half == 0 ? middle[p] : query.points[p + 4];
    }
    double separation = double(query.minSeparation);
    if (error > 0.0) separation = std::nextafter(separation + 2.0 * error, kInfinity);
    const float widened = floatAtLeast(separation);
    if (std::isinf(widened)) return std::nullopt;
    piece.minSeparation =
        error > 0.0 ? ccdCoveredSeparation(widened, largestMagnitude(piece.points)) : widened;
    return piece;
}

CcdQueryResult answerWithContinuation(const std::vector<CcdQuery>& queries, const CcdSolver& solve,
                                      int rounds) {
    CcdQueryResult result;
    if (queries.empty()) return result;
    std::vector<std::vector<Piece>> pieces(queries.size());
    const std::vector<CcdAnswer> first = solve(queries);
    for (std::size_t q = 0; q < queries.size(); ++q) {
        pieces[q].push_back({0.0, 1.0, queries[q], first[q]});
        result.boxes += first[q].boxes;
        result.continued += first[q].capped ? 1u : 0u;
    }

    for (int round = 0; round < rounds; ++round) {
        // Every open capped piece that can be halved, as two new queries.
        struct Split {
            std::size_t query, piece;
        };
        std::vector<Split> splits;
        std::vector<CcdQuery> halves;
        for (std::size_t q = 0; q < pieces.size(); ++q)
            openPieces(pieces[q], [&](std::size_t i) {
                if (!pieces[q][i].answer.capped) return;
                const std::optional<CcdQuery> early = halfOfTime(pieces[q][i].query, 0);
                const std::optional<CcdQuery> late = halfOfTime(pieces[q][i].query, 1);
                if (!early || !late) return; // stays capped
                splits.push_back({q, i});
                halves.push_back(*early);
                halves.push_back(*late);
            });
        if (splits.empty()) break;
        const std::vector<CcdAnswer> answers = solve(halves);
        // Replace each split piece by its halves, last split first so earlier indices stay valid.
        for (std::size_t s = splits.size(); s-- > 0;) {
            std::vector<Piece>& list = pieces[splits[s].query];
            const Piece whole = list[splits[s].piece];
            const double length = whole.length / 2;
            const Piece early{whole.start, length, halves[2 * s], answers[2 * s]};
            const Piece late{whole.start + length, length, halves[2 * s + 1], answers[2 * s + 1]};
            list[splits[s].piece] = early;
            list.insert(list.begin() + static_cast<std::ptrdiff_t>(splits[s].piece) + 1, late);
            result.boxes += answers[2 * s].boxes + answers[2 * s + 1].boxes;
        }
    }

    result.mayCollide.reserve(queries.size());
    result.toi.reserve(queries.size());
    result.cappedFlags.reserve(queries.size());
    for (const std::vector<Piece>& list : pieces) {
        const auto hit =
            std::find_if(list.begin(), list.end(), [](const Piece& p) { return p.answer.mayCollide; });
        const bool decided = std::any_of(
            list.begin(), list.end(), [](const Piece& p) { return p.answer.mayCollide && !p.answer.capped; });
        const bool capped = hit != list.end() && !decided;
        result.mayCollide.push_back(hit != list.end() ? 1 : 0);
        result.toi.push_back(hit != list.end() ? globalTime(hit->start, hit->length, hit->answer.toi) : 1.0f);
        result.cappedFlags.push_back(capped ? 1 : 0);
        result.capped += capped ? 1u : 0u;
    }
    return result;
}

} // namespace glcollide::passes
