// Segment observers of radial culling (issue 24; decision 0025, "Segment observers"; docs/culling.md):
// an object's "observer": [[x, y, z], [x, y, z]], each end tied to four of its nodes. On the device,
// against independent answers: the GPU's classification is the twin's where the GPU evaluates the
// GLSL as written (llvmpipe; its feet and cones within a few units in the last place), and on every
// device its feet and cones hold every sampled point's foot and fiber and each face it proves
// positive faces away from every sampled foot (double precision, no shared code); the whole culling
// pass on a corrugated cigar folded through itself frees faces that the exact oracle finds
// intersecting nothing along the motion, and frees more of the still cigar than its centroid does;
// the segment's ends follow their frames; a segment that leaves its surface frees nothing.

#include "cpu/collision_twin.hpp"
#include "cpu/radial_twin.hpp"
#include "model/flat_model.hpp"
#include "passes/radial_classify.hpp"
#include "passes/radial_culling.hpp"
#include "support/collision_buffers.hpp"
#include "support/glsl_as_written.hpp"
#include "support/radial_culling_run.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace glcollide {
namespace {

/// The sphere generator's surface (radius 0.5, 1,280 faces) scaled to a 3 m × 0.6 m × 0.6 m cigar
/// along x, corrugated: its radius times 1 + 0.3 sin(10.5 x), so that every other ring of faces
/// leans towards the middle (slopes up to 1.4) and turns its back on the centroid.
model::FlatModel cigarModel() {
    const std::string json =
        R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "cigar", "generator": {"type": "sphere", "radius": 0.5, "subdivisions": 3},
                   "mass": 1, "transform": {"scale": [6, 1.2, 1.2]}}]})";
    model::FlatModel model = model::flatten(parseScene(json, ".", "cigar"));
    for (glm::dvec3& p : model.positions) {
        const double factor = 1.0 + 0.3 * std::sin(10.5 * p.x);
        p.y *= factor;
        p.z *= factor;
    }
    return model;
}

std::vector<glm::vec3> floats(const std::vector<glm::dvec3>& xs) {
    return {xs.begin(), xs.end()};
}

/// The top of the right half (y > 0.3, 0 < x < 1.5) shoved 0.8 m along -x, through the top of the
/// left half that stays: real self-intersections, away from the axis.
std::vector<glm::vec3> folded(const std::vector<glm::vec3>& x0) {
    std::vector<glm::vec3> x1 = x0;
    for (glm::vec3& p : x1)
        if (p.y > 0.3f && p.x > 0.0f && p.x < 1.5f) p.x -= 0.8f;
    return x1;
}

// Every compared value (a unit axis, a cosine, a foot's u) lies within [-1, 1]: 2^-20 absolute is
// 16 units in the last place of 1, what a reciprocal-based division and square root (which
// llvmpipe need not round as C++ does) add over the few operations behind each.
bool nearlyEqual(const glm::vec4& a, const glm::vec4& b) {
    for (int i = 0; i < 4; ++i)
        if (!(std::abs(a[i] - b[i]) <= 9.5367431640625e-7f)) return false;
    return true;
}

/// A point x of a face at one time, its foot's u on the segment, x - foot(x), and the face's normal.
struct FiberSample {
    double u = 0.0;
    glm::dvec3 fiber{0.0}, normal{0.0};
};

/// Face f's corners, edge midpoints and centroid at five times of the substep (double).
std::vector<FiberSample> fiberSamples(const std::vector<std::uint32_t>& faces, std::size_t f,
                                      const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                      const passes::RadialObserver& o) {
    std::vector<FiberSample> out;
    for (int k = 0; k <= 4; ++k) {
        const double t = k / 4.0;
        const auto at = [&](glm::vec3 a, glm::vec3 b) { return glm::mix(glm::dvec3(a), glm::dvec3(b), t); };
        const glm::dvec3 p0 = at(x0[faces[3 * f]], x1[faces[3 * f]]),
                         p1 = at(x0[faces[3 * f + 1]], x1[faces[3 * f + 1]]),
                         p2 = at(x0[faces[3 * f + 2]], x1[faces[3 * f + 2]]);
        const glm::dvec3 a = at(o.start, o.end), b = at((*o.segment)[0], (*o.segment)[1]);
        for (const glm::dvec3& x :
             {p0, p1, p2, (p0 + p1) / 2.0, (p1 + p2) / 2.0, (p2 + p0) / 2.0, (p0 + p1 + p2) / 3.0}) {
            const double u = std::clamp(glm::dot(x - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            out.push_back({u, x - (a + u * (b - a)), glm::cross(p1 - p0, p2 - p0)});
        }
    }
    return out;
}

/// Every sample's u within `feet` and its fiber within `cone` ("every direction" holds all).
bool holdsItsFibers(const std::vector<FiberSample>& samples, glm::vec2 feet, glm::vec4 cone) {
    const glm::dvec3 axis(cone.x, cone.y, cone.z);
    for (const FiberSample& s : samples) {
        if (s.u < feet.x || s.u > feet.y) return false;
        // 1e-12: the double evaluation of this check itself.
        if (cone.w > -1.0f &&
            glm::dot(axis, s.fiber) / (glm::length(axis) * glm::length(s.fiber)) < double{cone.w} - 1e-12)
            return false;
    }
    return true;
}

/// n(t) . (x - foot(x)) > 0 at every sample.
bool facesAwayFromItsFeet(const std::vector<FiberSample>& samples) {
    return std::all_of(samples.begin(), samples.end(),
                       [](const FiberSample& s) { return glm::dot(s.normal, s.fiber) > 0.0; });
}

TEST(RadialSegmentObserverGl, TheClassificationFeetAndConesAreTheTwins) {
    const model::FlatModel model = cigarModel();
    const std::vector<glm::vec3> x0 = floats(model.positions), x1 = folded(x0);
    const auto faces = static_cast<std::uint32_t>(model.faceCount());
    const std::vector<std::uint32_t> faceObserver(faces, 0u);
    // The segment along the axis, moving a little during the substep (both ends differently).
    passes::RadialObserver o{
        glm::vec3(-2.7f, 0.0f, 0.0f), glm::vec3(-2.68f, 0.01f, 0.0f),
        std::array<glm::vec3, 2>{glm::vec3(2.7f, 0.0f, 0.0f), glm::vec3(2.69f, -0.01f, 0.005f)}};

    passes::DeviceBuffers b = test::collisionBuffers(x0, model.faceIndices);
    b.predictedPositions = gl::makeBuffer("predictedPositions", test::positionsWithUnitW(x1));
    passes::RadialClassifyPass pass(faceObserver, 1);
    pass.setObservers({o});
    pass.dispatch(b);
    const std::vector<std::uint32_t> mask = pass.readMask();
    std::vector<glm::vec4> cones(faces);
    std::vector<glm::vec2> feet(faces);
    pass.cones().download(0, cones.size() * sizeof(glm::vec4), cones.data());
    pass.feet().download(0, feet.size() * sizeof(glm::vec2), feet.data());

    const std::vector<glm::vec3> observers = {o.start, o.end};
    const cpu::RadialSegmentEnds ends = {glm::vec4((*o.segment)[0], 1.0f), glm::vec4((*o.segment)[1], 1.0f)};
    std::uint32_t positive = 0;
    for (std::uint32_t f = 0; f < faces; ++f) {
        const bool isPositive = (mask[f / 32] >> (f % 32) & 1u) != 0u;
        positive += isPositive ? 1u : 0u;
        if (test::deviceEvaluatesGlslAsWritten()) {
            // The decision is the twin's; the feet and cones pass through divisions and square
            // roots, which llvmpipe need not round as C++ does: within a few units in the last place.
            const cpu::RadialFaceView twin =
                cpu::radialFaceView(model.faceIndices, x0, x1, f, 0u, observers, ends);
            EXPECT_EQ(isPositive, twin.positive) << "face " << f;
            EXPECT_TRUE(nearlyEqual(cones[f], twin.cone)) << "face " << f;
            EXPECT_TRUE(nearlyEqual(glm::vec4(feet[f], 0.0f, 0.0f), glm::vec4(twin.feet, 0.0f, 0.0f)))
                << "face " << f;
        }
        // On every device: the GPU's feet and cone hold every sampled point's foot and fiber, and
        // a face it proves positive faces away from its sampled feet.
        const std::vector<FiberSample> samples = fiberSamples(model.faceIndices, f, x0, x1, o);
        EXPECT_TRUE(holdsItsFibers(samples, feet[f], cones[f])) << "face " << f;
        if (isPositive) {
            EXPECT_TRUE(facesAwayFromItsFeet(samples)) << "face " << f;
        }
    }
    RecordProperty("positive", static_cast<int>(positive));
    EXPECT_GT(positive, faces / 2) << "the fold turns a few faces; the rest stay positive";
    EXPECT_LT(positive, faces);
}

passes::RadialCullingConfig withSegment(const model::FlatModel& model, const glm::dvec3& a,
                                        const glm::dvec3& b) {
    passes::RadialObserverSettings settings;
    settings.objectObservers = {a};
    settings.objectObserverEnds = {b};
    return passes::radialCullingConfig(model, settings);
}

/// Σ w_k·x_k of one of the configuration's frames at positions x (double).
glm::dvec3 framePoint(const std::array<std::uint32_t, 4>& nodes, const std::array<float, 4>& weights,
                      const std::vector<glm::vec3>& x) {
    glm::dvec3 p(0.0);
    for (std::size_t k = 0; k < 4; ++k) p += static_cast<double>(weights[k]) * glm::dvec3(x[nodes[k]]);
    return p;
}

// As for user points (radial_user_observer_gl_test.cpp): four float weights up to about 2 times
// coordinates up to 3 m, summed in float: 1e-5 m bounds the rounding with margin at this size.
constexpr double kFloatTolerance = 1e-5;

TEST(RadialSegmentObserverGl, TheCullingPassFreesWhatTheOracleFindsIntersectingNothing) {
    const model::FlatModel model = cigarModel();
    const glm::dvec3 a(-2.7, 0.0, 0.0), b(2.7, 0.0, 0.0);
    const passes::RadialCullingConfig config = withSegment(model, a, b);
    ASSERT_EQ(config.surfaces.size(), 1u);
    ASSERT_TRUE(config.surfaces[0].segment);
    const std::vector<glm::vec3> x0 = floats(model.positions), x1 = folded(x0);
    const auto faces = static_cast<std::uint32_t>(model.faceCount());

    // Still: the segment frees every face; the centroid (the default observer) far fewer.
    const test::CullingRun still = test::runCulling(model, config, x0, x0);
    ASSERT_EQ(still.observers.size(), 1u);
    ASSERT_TRUE(still.observers[0].segment.has_value());
    EXPECT_LT(glm::length(glm::dvec3(still.observers[0].start) - a), kFloatTolerance);
    EXPECT_LT(glm::length(glm::dvec3((*still.observers[0].segment)[0]) - b), kFloatTolerance);
    EXPECT_EQ(still.winding[0], (passes::RadialWinding{1, false}));
    EXPECT_EQ(still.freeCount, faces);
    const test::CullingRun centroid =
        test::runCulling(model, passes::radialCullingConfig(model, passes::RadialObserverSettings{}), x0, x0);
    EXPECT_LT(centroid.freeCount, faces / 2);
    RecordProperty("still_free_segment", static_cast<int>(still.freeCount));
    RecordProperty("still_free_centroid", static_cast<int>(centroid.freeCount));

    // Folded through itself: the ends follow their frames; on llvmpipe the free faces are the
    // twin's; everywhere no free face intersects anything at nine times of the substep.
    const test::CullingRun run = test::runCulling(model, config, x0, x1);
    const passes::RadialSurface& s = config.surfaces[0];
    EXPECT_LT(glm::length(glm::dvec3(run.observers[0].end) - framePoint(s.frameNodes, s.frameWeights, x1)),
              kFloatTolerance);
    EXPECT_LT(glm::length(glm::dvec3((*run.observers[0].segment)[1]) -
                          framePoint(s.segmentFrameNodes, s.segmentFrameWeights, x1)),
              kFloatTolerance);
    if (test::deviceEvaluatesGlslAsWritten()) {
        const std::vector<glm::vec3> observers = {run.observers[0].start, run.observers[0].end};
        const cpu::RadialSegmentEnds ends = {glm::vec4((*run.observers[0].segment)[0], 1.0f),
                                             glm::vec4((*run.observers[0].segment)[1], 1.0f)};
        EXPECT_EQ(run.free, cpu::radialFreeFaces(model.faceIndices, x0, x1,
                                                 std::vector<std::uint32_t>(faces, 0u), observers, ends));
    }
    const std::vector<std::uint32_t> faceObject(faces, 0u);
    std::size_t intersecting = 0;
    int k = 0;
    for (const auto& pairs : cpu::twinIntersectionsAlongMotion(model.faceIndices, faceObject, x0, x1,
                                                               cpu::PairRules{false, true}, 8)) {
        ++k;
        intersecting = std::max(intersecting, pairs.size());
        for (const cpu::FacePair& p : pairs)
            EXPECT_FALSE(run.free[p[0]] || run.free[p[1]])
                << "faces " << p[0] << " and " << p[1] << " intersect at t = " << k << "/8, one of them free";
    }
    EXPECT_GT(intersecting, 0u) << "the fold must intersect, or the test shows nothing";
    EXPECT_GT(run.freeCount, faces / 3);
    RecordProperty("folded_free", static_cast<int>(run.freeCount));
}

// Cases built to defeat the observer: a segment that pokes out of its surface (the theorem's (b')
// fails: the faces it pierces meet every footprint) and one whose first end lies outside (the
// winding number around it is 0: the premise (a') fails, and the failure is counted). Neither may
// free a face, whatever the other faces' signs.
TEST(RadialSegmentObserverGl, ASegmentThatLeavesItsSurfaceFreesNothing) {
    const model::FlatModel model = cigarModel(); // the cigar's tips are at x = -3 and 3
    const std::vector<glm::vec3> x0 = floats(model.positions);
    const test::CullingRun out =
        test::runCulling(model, withSegment(model, {-2.7, 0, 0}, {3.5, 0, 0}), x0, x0);
    EXPECT_EQ(out.winding[0], (passes::RadialWinding{1, false})) << "its first end is inside";
    EXPECT_EQ(out.freeCount, 0u);
    const test::CullingRun outside =
        test::runCulling(model, withSegment(model, {-3.5, 0, 0}, {2.7, 0, 0}), x0, x0);
    EXPECT_EQ(outside.winding[0], (passes::RadialWinding{0, false}));
    EXPECT_EQ(outside.freeCount, 0u);
    EXPECT_EQ(outside.violatedStat, 1u) << "the failed premise is counted";
}

} // namespace
} // namespace glcollide
