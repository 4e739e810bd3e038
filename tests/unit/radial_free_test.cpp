// Decision 0025's theorem, checked on motions: a free face (positive for its observer, its
// footprint cone meeting no non-positive face's cone) intersects no other face of its closed
// surface — at the end of the substep and at eight times inside it, by the exact TriTri oracle
// (cpu::twinIntersections, GMP), which shares nothing with the classification. Surfaces: the
// sphere generator's closed surface (1,280 faces) around an observer at its centre, crumpled so
// that a cap is pushed through the far side (real self-intersections), and twisted; and a corrugated
// cigar around a segment observer (decision 0025, "Segment observers"), folded through itself.

#include "cpu/collision_twin.hpp"
#include "cpu/radial_twin.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace glcollide {
namespace {

struct Surface {
    std::vector<glm::vec3> x0;
    std::vector<std::uint32_t> faces;
};

Surface sphereSurface(const std::string& scale = "1") {
    const Scene scene =
        parseScene(R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.5, "subdivisions": 3}, "mass": 1,
                   "transform": {"scale": )" +
                       scale + "}}]}",
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

/// Checks the theorem for one substep x0 -> x1 with a still observer at `q`, or the still segment
/// from `q` to `segmentEnd`.
Tally expectFreeFacesIntersectNothing(const Surface& s, const std::vector<glm::vec3>& x1, glm::vec3 q,
                                      std::optional<glm::vec3> segmentEnd = std::nullopt) {
    const std::size_t faces = s.faces.size() / 3;
    const std::vector<std::uint32_t> faceObserver(faces, 0u);
    const std::vector<glm::vec3> observer = {q, q};
    cpu::RadialSegmentEnds ends;
    if (segmentEnd) ends = {glm::vec4(*segmentEnd, 1.0f), glm::vec4(*segmentEnd, 1.0f)};
    const std::vector<std::uint8_t> free =
        cpu::radialFreeFaces(s.faces, s.x0, x1, faceObserver, observer, ends);
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

// Decision 0025, "Segment observers": the same theorem with fibers from a segment's nearest point
// instead of rays from a point. A cigar (the sphere generator's surface scaled to 3 m x 0.6 m x
// 0.6 m) around a segment along its axis, corrugated (its radius times 1 + 0.3 sin(10.5 x): every
// other ring of faces leans towards the middle, slopes up to 1.4), then folded through itself.
std::vector<glm::vec3> corrugated(const Surface& s) {
    std::vector<glm::vec3> x = s.x0;
    for (glm::vec3& p : x) {
        const float factor = 1.0f + 0.3f * std::sin(10.5f * p.x);
        p.y *= factor;
        p.z *= factor;
    }
    return x;
}

TEST(RadialFree, ASegmentObserverFreesACorrugatedCigarThatItsMiddlePointCannot) {
    Surface s = sphereSurface("[6, 1.2, 1.2]");
    s.x0 = corrugated(s);
    const std::size_t faces = s.faces.size() / 3;
    const glm::vec3 a(-2.7f, 0.0f, 0.0f), b(2.7f, 0.0f, 0.0f);
    // Still: nothing intersects; the segment frees every face; the middle point (the centroid, the
    // default observer) frees fewer: the rings that lean towards the middle face it.
    const Tally segment = expectFreeFacesIntersectNothing(s, s.x0, a, b);
    const Tally point = expectFreeFacesIntersectNothing(s, s.x0, glm::vec3(0.0f));
    EXPECT_EQ(segment.intersecting, 0u);
    EXPECT_EQ(segment.free, faces);
    EXPECT_LT(point.free, segment.free);
    RecordProperty("still_free_segment", static_cast<int>(segment.free));
    RecordProperty("still_free_point", static_cast<int>(point.free));

    // Folded: the top of the right half (y > 0.3, 0 < x < 1.5) shoved 0.8 m along -x, through the
    // top of the left half that stays (a fold that never reaches the segment: faces that sweep
    // through it would free nothing of the surface).
    std::vector<glm::vec3> x1 = s.x0;
    for (std::size_t i = 0; i < x1.size(); ++i)
        if (s.x0[i].y > 0.3f && s.x0[i].x > 0.0f && s.x0[i].x < 1.5f) x1[i].x -= 0.8f;
    const Tally folded = expectFreeFacesIntersectNothing(s, x1, a, b);
    EXPECT_GT(folded.intersecting, 0u) << "the fold must really intersect, or the test shows nothing";
    EXPECT_GT(folded.free, faces / 3);
    RecordProperty("folded_free", static_cast<int>(folded.free));
    RecordProperty("folded_intersecting", static_cast<int>(folded.intersecting));

    // The surface's right end sags 0.4 m below the still segment, so that the tip's faces cross
    // the segment's end during the substep: the theorem's condition (b) fails, and the rule that
    // a face whose cone is every direction has every foot makes it free nothing of the surface.
    std::vector<glm::vec3> sagging = s.x0;
    for (std::size_t i = 0; i < sagging.size(); ++i)
        if (s.x0[i].x > 0.5f) sagging[i].y -= 0.4f;
    const Tally sag = expectFreeFacesIntersectNothing(s, sagging, a, b);
    EXPECT_EQ(sag.free, 0u);
}

} // namespace
} // namespace glcollide
