#pragma once
// Rational CCD queries rounded to the float queries the GPU decides, with the rounding covered:
// the float query's minimum separation is widened so that a float answer "no contact" still
// means "no contact" for the original rationals (docs/ccd.md, "query ccd: rounded inputs").

#include "cpu/oracle/exact_ccd.hpp"

#include <glm/vec3.hpp>
#include <gmpxx.h>

#include <array>

namespace glcollide::cpu {

/// The float nearest to `x` (round to nearest, ties to even; subnormals as IEEE binary32 has
/// them). Exact for any size of numerator and denominator: unlike mpq_class::get_d (which
/// truncates to double) followed by a float conversion, it rounds once. Throws Error when x rounds
/// to infinity (|x| >= 2^128 - 2^103).
float nearestFloat(const mpq_class& x);

/// The least float >= x. Throws Error when there is none (x > the largest float).
float floatAtLeast(const mpq_class& x);

/// A CCD query rounded to float, in the order of RationalCcdQuery (4 points at t = 0, then at t = 1).
struct RoundedCcdQuery {
    std::array<glm::vec3, 8> points;
    /// The float CCD's minimum separation: minSeparation + 2 * roundingError rounded up to a float
    /// (raised, when it is not 0, to a value the float CCD's normalization keeps normal: see
    /// coverRounding). 0 only when minSeparation is 0 and every (scaled) coordinate is a float.
    float minSeparation = 0.0f;
    /// The largest |x - nearestFloat(x)| over the query's 24 (scaled) coordinates, exactly.
    mpq_class roundingError;
    /// Contact queries (minSeparation 0) only: axis k was multiplied by 2^axisScale[k] before
    /// rounding; 0 otherwise.
    std::array<long, 3> axisScale{};
};

/// Rounds every coordinate to the nearest float and covers the rounding: the float CCD (which
/// excludes a box only when one coordinate of F exceeds its minimum separation there, per axis)
/// answering "no contact within RoundedCcdQuery::minSeparation" for the rounded points implies
/// that the original points never come within `minSeparation` (docs/ccd.md). `minSeparation` >= 0.
/// For a contact query (minSeparation 0) each axis is first scaled by the power of two that brings
/// its largest magnitude into [0.5, 1) (contactAxisScale): contact and its time are the same for
/// any scaling of an axis, and the cover, one number for the three axes, then weighs on each axis
/// in proportion to its own magnitude, as the float CCD's error bound does. Times of impact need
/// no mapping back. Throws Error when a coordinate or the widened separation does not fit in a
/// float.
RoundedCcdQuery roundCcdQuery(const RationalCcdQuery& query, const mpq_class& minSeparation);

/// Per axis, the exponent k with 2^k * (the axis's largest coordinate magnitude) in [0.5, 1)
/// (0 for an axis whose coordinates are all 0).
std::array<long, 3> contactAxisScale(const RationalCcdQuery& query);

/// The cover alone: the least float >= minSeparation + 2 * roundingError, raised when it is not 0
/// to ccdSeparationFloor (core/ccd_cover.hpp) of the largest coordinate magnitude of `points`, so
/// that neither the separation nor its value normalized inside the float CCD is subnormal, which
/// a device that flushes subnormals would read as 0.
float coverRounding(const std::array<glm::vec3, 8>& points, const mpq_class& minSeparation,
                    const mpq_class& roundingError);

} // namespace glcollide::cpu
