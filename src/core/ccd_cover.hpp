#pragma once
// The float CCD's minimum separation after a rounding cover (docs/ccd.md, "query ccd"): widened
// separations are raised, when they are not 0, so that neither the separation nor its normalized
// value inside shaders/common/ccd.glsl is subnormal, which a device that flushes subnormals would
// read as 0 and so lose the cover. Shared by the rational rounding (cpu/oracle/ccd_rounding.cpp)
// and the time-split continuation of capped queries (passes/ccd_continuation.cpp).

#include <algorithm>
#include <cmath>
#include <limits>

namespace glcollide {

/// The least separation to use instead of a positive `separation` for a query whose largest
/// coordinate magnitude is `largest`: 2^-126 (the least normal float) and 2^-125 * largest.
/// ccd.glsl multiplies the separation by its normalizing scale s, a power of two with
/// largest * s in [0.5, 1) (or s = 2^126 and more when largest is subnormal or 0), so s >= 0.5 /
/// largest and separation * s >= 2^-126 whenever separation >= 2^-125 * largest.
inline float ccdSeparationFloor(float largest) {
    const float leastNormal = std::numeric_limits<float>::min();        // 2^-126
    return std::max(leastNormal, std::ldexp(std::fabs(largest), -125)); // exact: a power-of-two scaling
}

/// `separation` (>= 0) raised to ccdSeparationFloor(largest) when it is positive; 0 stays 0.
inline float ccdCoveredSeparation(float separation, float largest) {
    return separation > 0.0f ? std::max(separation, ccdSeparationFloor(largest)) : 0.0f;
}

} // namespace glcollide
