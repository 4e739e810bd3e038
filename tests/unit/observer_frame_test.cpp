// model::observerFrame (decision 0025, "User observers") against what an affine frame must do: give
// back the point at the initial positions, follow any affine map of the object exactly, use four
// distinct nodes, and refuse an object that spans no volume; and follow a twist where it is tied to
// the point's nearest nodes.

#include "model/observer_frame.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

namespace glcollide {
namespace {

glm::dvec3 at(const model::ObserverFrame& f, const std::vector<glm::dvec3>& x) {
    glm::dvec3 p(0.0);
    for (int k = 0; k < 4; ++k)
        p += f.weights[static_cast<std::size_t>(k)] * x[f.nodes[static_cast<std::size_t>(k)]];
    return p;
}

std::vector<glm::dvec3> randomCloud(unsigned seed, std::size_t n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<glm::dvec3> x;
    for (std::size_t i = 0; i < n; ++i) x.emplace_back(u(rng), 0.5 * u(rng), 0.2 * u(rng));
    return x;
}

TEST(ObserverFrame, GivesThePointBackAndFollowsAffineMapsExactly) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        const std::vector<glm::dvec3> x = randomCloud(seed, 50);
        const glm::dvec3 point(0.1, -0.05, 0.02 * seed);
        const model::ObserverFrame f = model::observerFrame(x, point);
        EXPECT_EQ(std::set<std::uint32_t>(f.nodes.begin(), f.nodes.end()).size(), 4u);
        EXPECT_NEAR(f.weights[0] + f.weights[1] + f.weights[2] + f.weights[3], 1.0, 1e-12);
        // 1e-12 m: double rounding of a 3×3 solve on coordinates of size 1.
        EXPECT_LT(glm::length(at(f, x) - point), 1e-12) << seed;
        // An affine map (rotation, shear, scale, translation) carries the frame with the point.
        const glm::dmat3 m(glm::dvec3(0.8, 0.3, -0.2), glm::dvec3(-0.1, 1.2, 0.4),
                           glm::dvec3(0.25, 0.0, 0.9));
        const glm::dvec3 shift(3.0, -2.0, 7.5);
        std::vector<glm::dvec3> moved;
        for (const glm::dvec3& p : x) moved.push_back(m * p + shift);
        EXPECT_LT(glm::length(at(f, moved) - (m * point + shift)), 1e-11) << seed;
    }
}

TEST(ObserverFrame, RefusesAnObjectThatSpansNoVolume) {
    std::vector<glm::dvec3> sheet;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) sheet.emplace_back(0.1 * i, 0.0, 0.1 * j);
    EXPECT_THROW((void)model::observerFrame(sheet, glm::dvec3(0.2, 0.1, 0.2)), std::invalid_argument);
    EXPECT_THROW(
        (void)model::observerFrame({glm::dvec3(0.0), glm::dvec3(1.0), glm::dvec3(2.0)}, glm::dvec3(0.0)),
        std::invalid_argument);
    sheet[7].y = 0.05; // one node lifted by half a spacing: a volume
    EXPECT_NO_THROW((void)model::observerFrame(sheet, glm::dvec3(0.2, 0.1, 0.2)));
}

/// A tube of `around` x `along` nodes, radius 0.08 m, from y = -0.25 to 0.25, each ring turned by
/// `twist` radians times its height / 0.5 m (a sleeve twisted about its axis).
std::vector<glm::dvec3> tube(int around, int along, double twist) {
    std::vector<glm::dvec3> x;
    for (int j = 0; j < along; ++j) {
        const double y = 0.25 - 0.5 * j / (along - 1);
        for (int i = 0; i < around; ++i) {
            const double angle = 2.0 * 3.141592653589793 * i / around + twist * y / 0.5;
            x.emplace_back(0.08 * std::cos(angle), y, 0.08 * std::sin(angle));
        }
    }
    return x;
}

// Local frames: a point on a sleeve's axis is tied to nodes around it, so a twist about the axis
// (far from affine over the whole sleeve) carries it along the axis. The frame spread over the whole
// sleeve would mix rings turned against each other.
TEST(ObserverFrame, APointOnATwistedSleevesAxisStaysOnTheAxis) {
    const std::vector<glm::dvec3> rest = tube(32, 20, 0.0);
    for (const double y : {-0.2, -0.1, 0.0, 0.13, 0.22}) {
        const glm::dvec3 point(0.0, y, 0.0);
        const model::ObserverFrame f = model::observerFrame(rest, point);
        EXPECT_LT(glm::length(at(f, rest) - point), 1e-12) << y;
        for (std::size_t k = 0; k < 4; ++k) {
            EXPECT_LE(std::abs(f.weights[k]), model::kLocalFrameWeight) << y;
            // Local: every frame node within three ring spacings (3 x 2.6 cm) of the point's height.
            EXPECT_LT(std::abs(rest[f.nodes[k]].y - y), 0.08) << y;
        }
        for (const double twist : {1.0, 3.0, 6.0}) { // up to about a full turn end to end
            const glm::dvec3 moved = at(f, tube(32, 20, twist));
            // The rings near the point turn by at most twist x (3 spacings / 0.5 m) against each
            // other: the point leaves the axis by a small fraction of the radius (8 cm).
            EXPECT_LT(std::hypot(moved.x, moved.z), 0.02) << "y " << y << ", twist " << twist;
            EXPECT_NEAR(moved.y, y, 0.01) << "y " << y << ", twist " << twist;
        }
    }
}

} // namespace
} // namespace glcollide
