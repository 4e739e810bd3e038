#pragma once
// Exact continuous collision detection in rational arithmetic (GMP): the oracle the conservative
// float CCD (shaders/common/ccd.glsl) is judged by. Every point moves linearly over t in [0, 1]
// from its position at t = 0 to its position at t = 1; the oracle decides exactly whether the
// primitives touch (minimum separation 0) at some t, and brackets the earliest such t.
//
// Semantics: closed sets (touching at an edge, a vertex, at t = 0 or t = 1 counts); a zero-area
// triangle is the union of its edges, a zero-length edge is its point; coplanar motion is decided
// in the plane. No epsilon anywhere: the decision uses the coplanarity polynomial's real roots,
// isolated by Sturm sequences, and the sign of each inside condition at those roots (a condition
// that shares the root, found by a gcd over Q, is exactly 0). Method: docs/ccd.md.

#include <glm/vec3.hpp>
#include <gmpxx.h>

#include <array>
#include <string>
#include <vector>

namespace glcollide::cpu {

struct RationalPoint {
    mpq_class x, y, z;
};

/// Four points at t = 0, then the same four at t = 1. Vertex-face: the vertex, then the
/// triangle's corners. Edge-edge: edge A's two ends, then edge B's (the CCD benchmark's order).
using RationalCcdQuery = std::array<RationalPoint, 8>;

/// The oracle's answer. When `touch`, the earliest time of contact lies in [toiLo, toiHi]
/// (toiLo == toiHi when it is rational and found exactly; otherwise toiHi - toiLo <= 2^-64).
struct ExactCcdResult {
    bool touch = false;
    mpq_class toiLo, toiHi;
};

ExactCcdResult exactVertexFaceCcd(const RationalCcdQuery& query);
ExactCcdResult exactEdgeEdgeCcd(const RationalCcdQuery& query);

/// Doubles and floats are rationals: the exact query of a floating-point one.
RationalCcdQuery rationalQuery(const std::array<glm::dvec3, 8>& points);

/// One query of the CCD benchmark (Wang et al. 2021, "Sample-Queries") with its ground truth.
struct SampleCcdQuery {
    RationalCcdQuery points;
    bool truth = false;
};

/// Reads a Sample-Queries CSV file (8 rows per query, 7 integer fields per row: numerator and
/// denominator of x, y and z, then the ground truth) with readCcdQueryCsv (ccd_query_csv.hpp), which
/// also reads rows of decimal numbers; every query must have its ground truth. Throws Error (a
/// std::runtime_error) naming the line.
std::vector<SampleCcdQuery> readSampleCcdQueries(const std::string& path);

/// Reads the points of a CCD query CSV with or without the ground-truth column: rows of 6 integer
/// fields (the Scalable-CCD dataset's queries/*.csv) or 7 (Sample-Queries), the same in every row;
/// spaces around the numbers are allowed (readCcdQueryCsv). Throws glcollide::Error naming the line.
std::vector<RationalCcdQuery> readCcdQueryPoints(const std::string& path);

/// Writes queries in the Sample-Queries layout (7 fields per row, fractions in lowest terms, the
/// 7th the truth as 0 or 1), so that readSampleCcdQueries and the benchmark's readers read them
/// back exactly. Throws std::runtime_error naming the file.
void writeSampleCcdQueries(const std::string& path, const std::vector<SampleCcdQuery>& queries);

} // namespace glcollide::cpu
