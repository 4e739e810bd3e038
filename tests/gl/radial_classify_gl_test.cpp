// RadialClassify (radial view-based culling's classification, docs/culling.md) on the device:
// the GPU's mask against the same GLSL compiled as C++ (cpu::radialPositiveMask: bit-identical
// where the GPU evaluates the GLSL as written, llvmpipe), and on every device against exact
// rational arithmetic (a face the GPU proves positive has four exactly positive Bernstein
// coefficients, so phi > 0 over the whole substep). Surfaces: the sphere generator's closed
// surface with its observer at the centre, at rest (every face positive), jittered, crumpled so
// that some faces turn their back on the observer, and with an observer outside.

#include "cpu/oracle/exact_radial.hpp"
#include "cpu/radial_twin.hpp"
#include "cpu/collision_twin.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/radial_classify.hpp"
#include "passes/radial_culling.hpp"
#include "support/collision_buffers.hpp"
#include "support/glsl_as_written.hpp"
#include "support/radial_culling_run.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <string>

namespace glcollide {
namespace {

struct Surface {
    std::vector<glm::vec3> x0;
    std::vector<std::uint32_t> faces;
};

/// The sphere generator's surface (radius 0.5 m around the origin, faces outward).
Surface sphereSurface(int subdivisions) {
    const std::string json =
        R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.5, "subdivisions": )" +
        std::to_string(subdivisions) + R"(}, "mass": 1}]})";
    const Scene scene = parseScene(json, ".", "sphere");
    Surface s;
    for (const glm::dvec3& p : scene.bodies.at(0).positions) s.x0.emplace_back(p);
    for (const auto& f : scene.bodies.at(0).faces) s.faces.insert(s.faces.end(), f.begin(), f.end());
    return s;
}

/// Every face and node given to one observer at the centroid of all nodes, no ghosts.
passes::RadialCullingConfig oneObserver(std::uint32_t faces, std::size_t nodes) {
    passes::RadialCullingConfig config;
    config.faceObserver.assign(faces, 0u);
    config.surfaces.resize(1);
    config.surfaces[0].nodeCount = static_cast<std::uint32_t>(nodes);
    config.ghosts.nodeCount = static_cast<std::uint32_t>(nodes);
    config.nodeObserver.assign(nodes, 0u);
    return config;
}

struct Outcome {
    std::uint32_t positive = 0, faces = 0;
};

/// Classifies on the GPU and checks it against the twin (llvmpipe) and the exact coefficients.
Outcome classify(const Surface& s, const std::vector<glm::vec3>& x1,
                 const std::vector<std::uint32_t>& faceObserver,
                 const std::vector<passes::RadialObserver>& observers) {
    passes::DeviceBuffers b = test::collisionBuffers(s.x0, s.faces);
    b.predictedPositions = gl::makeBuffer("predictedPositions", test::positionsWithUnitW(x1));
    passes::RadialClassifyPass pass(faceObserver, static_cast<std::uint32_t>(observers.size()));
    pass.setObservers(observers);
    pass.dispatch(b);
    const std::vector<std::uint32_t> mask = pass.readMask();

    std::vector<glm::vec3> ends;
    for (const passes::RadialObserver& o : observers) ends.insert(ends.end(), {o.start, o.end});
    // llvmpipe evaluates the GLSL as written: there the mask is the twin's bit for bit. Another
    // compiler may round differently (and prove a few more or fewer faces); the exact check below
    // holds everywhere.
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(mask, cpu::radialPositiveMask(s.faces, s.x0, x1, faceObserver, ends));
    }
    Outcome out;
    out.faces = static_cast<std::uint32_t>(faceObserver.size());
    for (std::uint32_t f = 0; f < out.faces; ++f) {
        if ((mask[f / 32] >> (f % 32) & 1u) == 0u) continue;
        ++out.positive;
        const std::uint32_t o = faceObserver[f];
        EXPECT_NE(o, passes::kNoRadialObserver) << "face " << f << " has no observer but is positive";
        if (o == passes::kNoRadialObserver) continue;
        const std::uint32_t* n = &s.faces[3 * std::size_t{f}];
        EXPECT_TRUE(cpu::exactlyRadialPositive({s.x0[n[0]], s.x0[n[1]], s.x0[n[2]], observers[o].start},
                                               {x1[n[0]], x1[n[1]], x1[n[2]], observers[o].end}))
            << "face " << f << ": proven positive on the GPU, not exactly positive";
    }
    for (std::size_t w = out.faces / 32; w < mask.size(); ++w) // bits past the last face stay clear
        EXPECT_EQ(mask[w] >> (out.faces % 32), 0u);
    return out;
}

TEST(RadialClassifyGl, AClosedSurfaceAroundItsObserver) {
    const Surface s = sphereSurface(3); // 1,280 faces
    const std::uint32_t faces = static_cast<std::uint32_t>(s.faces.size() / 3);
    const std::vector<std::uint32_t> all(faces, 0u);
    const std::vector<passes::RadialObserver> centre = {{glm::vec3(0.0f), glm::vec3(0.0f)}};

    // At rest: every face of a convex closed surface is positive for its centre.
    EXPECT_EQ(classify(s, s.x0, all, centre).positive, faces);

    // Jittered by up to 2 mm (the faces are ~7 cm) and the observer moving 1 cm: still all.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<glm::vec3> x1 = s.x0;
    for (glm::vec3& x : x1) x += 0.002f * glm::vec3(u(rng), u(rng), u(rng));
    EXPECT_EQ(classify(s, x1, all, {{glm::vec3(0.0f), glm::vec3(0.01f, 0.0f, 0.0f)}}).positive, faces);

    // Crumpled: nodes of one cap pushed through the centre to the far side during the substep.
    // The faces around them turn their back on the observer: not positive, the rest still are.
    std::vector<glm::vec3> crumpled = s.x0;
    std::uint32_t moved = 0;
    for (glm::vec3& x : crumpled)
        if (x.y > 0.4f) x.y = -0.2f, ++moved;
    ASSERT_GT(moved, 10u);
    const Outcome c = classify(s, crumpled, all, centre);
    EXPECT_LT(c.positive, faces);
    EXPECT_GT(c.positive, faces / 2);

    // Faces without an observer are never positive. An observer outside the ball, 4 radii from
    // its centre, is behind exactly the faces it cannot see: all but the visible cap, which covers
    // (1 - 1/4) / 2 = 37.5 % of the sphere, so about 62.5 % of the faces are positive.
    std::vector<std::uint32_t> half(faces, passes::kNoRadialObserver);
    for (std::uint32_t f = 0; f < faces; f += 2) half[f] = 0u;
    EXPECT_EQ(classify(s, s.x0, half, centre).positive, (faces + 1) / 2);
    const Outcome outside =
        classify(s, s.x0, all, {{glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(0.0f, 2.0f, 0.0f)}});
    RecordProperty("crumpled_positive", static_cast<int>(c.positive));
    RecordProperty("outside_positive", static_cast<int>(outside.positive));
    EXPECT_GT(outside.positive, faces / 2);
    EXPECT_LT(outside.positive, faces * 3 / 4);
}

// The whole culling pass (RadialObservers, RadialClassify, RadialFree) on the sphere surface
// whose cap is shoved through its far side during the substep: the observer is the nodes'
// centroid at both ends (the CPU's double mean, within the float sum's rounding); the free mask
// is the twin's (cpu::radialFreeFaces with the GPU's observers) bit for bit where the GPU
// evaluates the GLSL as written; on every device no face the GPU calls free intersects anything
// at eight times of the substep (the exact TriTri oracle), and the counts reach the statistics.
TEST(RadialClassifyGl, TheCullingPassFreesWhatTheTwinFreesAndNothingThatIntersects) {
    const Surface s = sphereSurface(3);
    const auto faces = static_cast<std::uint32_t>(s.faces.size() / 3);
    std::vector<glm::vec3> x1 = s.x0;
    for (std::size_t i = 0; i < x1.size(); ++i)
        if (s.x0[i].y > 0.3f && s.x0[i].x > 0.0f) x1[i].x -= 0.6f;
    const passes::RadialCullingConfig config = oneObserver(faces, s.x0.size());
    passes::RadialCullingPass pass(config);
    passes::AppendLists lists(0);
    test::runRadialCulling(pass, lists, s.x0, x1, s.faces);

    // The observer: the centroid. A fixed-order float sum of n terms of size <= |x| is within
    // n * 2^-24 * max|x| of the exact sum, so the mean is within 2^-24 * max|x| * (1 + small): 1e-6 m here.
    const std::vector<passes::RadialObserver> q = pass.readObservers();
    ASSERT_EQ(q.size(), 1u);
    glm::dvec3 c0(0.0), c1(0.0);
    for (std::size_t i = 0; i < s.x0.size(); ++i) c0 += glm::dvec3(s.x0[i]), c1 += glm::dvec3(x1[i]);
    c0 /= static_cast<double>(s.x0.size());
    c1 /= static_cast<double>(s.x0.size());
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(q[0].start[k], c0[k], 1e-6);
        EXPECT_NEAR(q[0].end[k], c1[k], 1e-6);
    }

    const std::vector<std::uint32_t> mask = pass.readFreeMask();
    const std::vector<std::uint8_t> twin =
        cpu::radialFreeFaces(s.faces, s.x0, x1, config.faceObserver, {q[0].start, q[0].end});
    std::uint32_t gpuFree = 0, twinFree = 0;
    std::vector<std::uint8_t> free(faces);
    for (std::uint32_t f = 0; f < faces; ++f) {
        free[f] = static_cast<std::uint8_t>(mask[f / 32] >> (f % 32) & 1u);
        gpuFree += free[f];
        twinFree += twin[f];
    }
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(free, twin) << "GPU free " << gpuFree << ", twin free " << twinFree;
    }
    EXPECT_GT(gpuFree, 0u);
    EXPECT_LT(gpuFree, faces) << "the fold must leave faces that are not free";
    EXPECT_EQ(lists.stat(GLC_STAT_RADIAL_FREE), gpuFree);
    EXPECT_GT(lists.stat(GLC_STAT_RADIAL_NON_POSITIVE), 0u);

    const std::vector<std::uint32_t> faceObject(faces, 0u);
    const cpu::PairRules self{false, true};
    std::size_t intersecting = 0, k = 0;
    for (const auto& pairs : cpu::twinIntersectionsAlongMotion(s.faces, faceObject, s.x0, x1, self, 8)) {
        ++k;
        intersecting = std::max(intersecting, pairs.size());
        for (const cpu::FacePair& p : pairs)
            EXPECT_FALSE(free[p[0]] || free[p[1]])
                << "faces " << p[0] << " and " << p[1] << " intersect at t = " << k
                << "/8, one of them free on the GPU";
    }
    EXPECT_GT(intersecting, 0u) << "the fold must really intersect, or the test shows nothing";
}

TEST(RadialClassifyGl, BadObserverIndicesAreRefused) {
    const std::vector<std::uint32_t> outOfRange = {0u, 3u};
    EXPECT_THROW(passes::RadialClassifyPass(outOfRange, 2u), Error);
    passes::RadialClassifyPass pass(std::vector<std::uint32_t>{0u, passes::kNoRadialObserver}, 1u);
    EXPECT_THROW(pass.setObservers({}), Error);
}

// Why the observer check (RadialWinding): two nested spheres given to one observer at their centre
// form a surface that winds twice around it. Every face is positive and no cone meets a
// non-positive one, so without the check all would be free — yet the inner sphere, growing to
// three times its radius during the substep, passes through the outer one (the exact oracle finds
// the pairs). The winding number is 2: nothing may be freed. (The engine never builds such a
// surface: its objects are connected; this is the theorem's premise tested on its own.)
TEST(RadialClassifyGl, ASurfaceWoundTwiceAroundItsObserverFreesNothing) {
    const Surface outer = sphereSurface(2);
    Surface both = outer;
    const auto offset = static_cast<std::uint32_t>(outer.x0.size());
    for (const glm::vec3& p : outer.x0) both.x0.push_back(0.5f * p); // the inner sphere, radius 0.25 m
    for (std::uint32_t n : outer.faces) both.faces.push_back(offset + n);
    std::vector<glm::vec3> x1 = both.x0;
    for (std::size_t i = offset; i < x1.size(); ++i) x1[i] *= 3.0f; // grows through the outer one
    const auto faces = static_cast<std::uint32_t>(both.faces.size() / 3);

    const passes::RadialCullingConfig config = oneObserver(faces, both.x0.size());
    passes::RadialCullingPass pass(config);
    passes::AppendLists lists(0);
    test::runRadialCulling(pass, lists, both.x0, x1, both.faces);

    ASSERT_EQ(pass.readWinding(), (std::vector<passes::RadialWinding>{{2, false}}));
    EXPECT_EQ(lists.stat(GLC_STAT_RADIAL_NON_POSITIVE), 0u)
        << "every face positive: only the winding stops it";
    EXPECT_EQ(lists.stat(GLC_STAT_RADIAL_FREE), 0u);
    EXPECT_EQ(lists.stat(GLC_STAT_RADIAL_VIOLATED), 1u);
    const std::vector<std::uint32_t> faceObject(faces, 0u);
    std::size_t intersecting = 0;
    for (const auto& pairs : cpu::twinIntersectionsAlongMotion(both.faces, faceObject, both.x0, x1,
                                                               cpu::PairRules{false, true}, 8))
        intersecting = std::max(intersecting, pairs.size());
    EXPECT_GT(intersecting, 0u) << "the inner sphere must really pass through the outer one";
}

} // namespace
} // namespace glcollide
