#pragma once
// The winding number of a closed triangle surface around a point, computed without any of the
// engine's code, for the unit tests of clusters and skeletons: the sum of the faces' signed solid
// angles over 4π (Van Oosterom & Strackee 1983), in double.

#include "model/ghost_triangles.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace glcollide::test {

inline double windingNumber(const std::vector<model::Triangle>& faces, const std::vector<glm::dvec3>& x,
                            const glm::dvec3& q) {
    double sum = 0.0;
    for (const model::Triangle& t : faces) {
        const glm::dvec3 a = x[t[0]] - q, b = x[t[1]] - q, c = x[t[2]] - q;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double numerator = glm::dot(a, glm::cross(b, c));
        const double denominator =
            la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        sum += 2.0 * std::atan2(numerator, denominator);
    }
    return sum / (4.0 * std::numbers::pi);
}

} // namespace glcollide::test
