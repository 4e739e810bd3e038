#pragma once
// The oracle of the restitution tests (ground_impact_gl_test.cpp, contact_impact_gl_test.cpp): one
// node's free flight under both integrators' shared recurrence (v += h·g, then y += h·v), from y0 at
// rest, until the substep whose end reaches the band's top; its impact speed is the free fall from
// that substep's start to the top; it then leaves the top at e times that speed. A few lines of
// double arithmetic that share nothing with the engine.

#include <algorithm>
#include <cmath>

namespace glcollide::test {

struct Bounce {
    double apex = 0.0;        ///< the highest height after the impact
    double impactSpeed = 0.0; ///< the speed it reaches the band's top with
};

inline Bounce oracleBounce(double y0, double top, double e, double g, double h) {
    double y = y0, v = 0.0;
    for (;;) {
        const double vNext = v - h * g, yNext = y + h * vNext;
        if (yNext <= top) break;
        y = yNext;
        v = vNext;
    }
    Bounce b;
    b.impactSpeed = std::sqrt(v * v + 2.0 * g * (y - top));
    y = top;
    v = e * b.impactSpeed;
    b.apex = y;
    while (v > 0.0) {
        v -= h * g;
        y += h * v;
        b.apex = std::max(b.apex, y);
    }
    return b;
}

} // namespace glcollide::test
