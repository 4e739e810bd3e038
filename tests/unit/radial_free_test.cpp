// Decision 0025's theorem, checked on motions: a free face (positive for its observer, its
// footprint cone meeting no non-positive face's cone) intersects no other face of its closed
// surface — at the end of the substep and at eight times inside it, by the exact TriTri oracle
// (cpu::twinIntersections, GMP), which shares nothing with the classification. Surfaces: the
// sphere generator's closed surface (1,280 faces) around an observer at its centre, crumpled so
// that a cap is pushed through the far side (real self-intersections), and twisted.

#include "cpu/collision_twin.hpp"
#include "cpu/radial_twin.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <string>

namespace glcollide {
namespace {

struct Surface {
    std::vector<glm::vec3> x0;
    std::vector<std::uint32_t> faces;
};

Surface sphereSurface() {
    const Scene scene =
        parseScene(R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.5, "subdivisions": 3}, "mass": 1}]})",
                   ".", "sphere");
    Surface s;
    // Surface nodes come first (docs/scene-format.md): the faces use only those.
    for (const glm::dvec3& p : scene.bodies.at(0).positions) s.x0.emplace_back(p);
    for (const auto& f : scene.bodies.at(0).faces) s.faces.insert(s.faces.end(), f.begin(), f.end());
    return s;
}

struct Tally {
    std::size_t free = 0, intersecting = 0;
};

/// Checks the theorem for one substep x0 -> x1 with a still observer at `q`.
Tally expectFreeFacesIntersectNothing(const Surface& s, const std::vector<glm::vec3>& x1, glm::vec3 q) {
    const std::size_t faces = s.faces.size() / 3;
    const std::vector<std::uint32_t> faceObserver(faces, 0u);
    const std::vector<glm::vec3> observer = {q, q};
    const std::vector<std::uint8_t> free = cpu::radialFreeFaces(s.faces, s.x0, x1, faceObserver, observer);
    Tally tally;
    for (std::uint8_t f : free) tally.free += f;
    const std::vector<std::uint32_t> faceObject(faces, 0u);
    const cpu::PairRules self{false, true};
    int k = 0;
    for (const auto& pairs : cpu::twinIntersectionsAlongMotion(s.faces, faceObject, s.x0, x1, self, 8)) {
        ++k;
        tally.intersecting = std::max(tally.intersecting, pairs.size());
        for (const cpu::FacePair& p : pairs)
            EXPECT_FALSE(free[p[0]] || free[p[1]])
                << "faces " << p[0] << " and " << p[1] << " intersect at t = " << k << "/8, one of them free";
    }
    return tally;
}

TEST(RadialFree, AFreeFaceIntersectsNothingWhenTheSurfaceFoldsThroughItself) {
    const Surface s = sphereSurface();
    const std::size_t faces = s.faces.size() / 3;
    // The observer inside the ball, away from the fold below: faces that sweep past close to the
    // observer have wide cones (up to "everything"), which leave nothing free.
    const glm::vec3 q(0.0f, -0.35f, 0.0f);
    // At rest: every face positive, none non-positive: every face is free, nothing intersects.
    const Tally rest = expectFreeFacesIntersectNothing(s, s.x0, q);
    EXPECT_EQ(rest.free, faces);
    EXPECT_EQ(rest.intersecting, 0u);

    // The +x half of the upper cap (y > 0.3, x > 0) shoved by 0.6 m in -x, through the -x half
    // that stays: the surface passes through itself near the top.
    std::vector<glm::vec3> x1 = s.x0;
    for (std::size_t i = 0; i < x1.size(); ++i)
        if (s.x0[i].y > 0.3f && s.x0[i].x > 0.0f) x1[i].x -= 0.6f;
    const Tally crumpled = expectFreeFacesIntersectNothing(s, x1, q);
    EXPECT_GT(crumpled.intersecting, 0u) << "the fold must really intersect, or the test shows nothing";
    EXPECT_GT(crumpled.free, 0u);
    RecordProperty("crumpled_free", static_cast<int>(crumpled.free));
    RecordProperty("crumpled_intersecting", static_cast<int>(crumpled.intersecting));

    // Twisted: the upper half turned by up to 120 degrees about y (no fold through the observer).
    std::vector<glm::vec3> twisted = s.x0;
    for (std::size_t i = 0; i < twisted.size(); ++i) {
        const float angle = glm::radians(120.0f) * std::max(s.x0[i].y, 0.0f) / 0.5f;
        const float c = std::cos(angle), sn = std::sin(angle);
        twisted[i] = glm::vec3(c * s.x0[i].x + sn * s.x0[i].z, s.x0[i].y, -sn * s.x0[i].x + c * s.x0[i].z);
    }
    const Tally twist = expectFreeFacesIntersectNothing(s, twisted, glm::vec3(0.0f));
    RecordProperty("twisted_free", static_cast<int>(twist.free));
}

} // namespace
} // namespace glcollide
