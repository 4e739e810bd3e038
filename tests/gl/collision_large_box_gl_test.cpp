// Leaf boxes with thousands of faces. llvmpipe ends a shader invocation after 65535 loop
// iterations in total (gallivm's loop limiter), so a kernel that walks a big box pair in one
// invocation silently stops early there; an earlier expansion kernel lost 30-90 % of the
// candidates of boxes with over ~1000 faces, which the small differential tests never reached.
// Two tet boxes pushed into each other, 40 cells a side (9600 faces each, ~2400 per depth-1 box):
// every depth must give exactly the brute-force twin's candidates.

#include "cpu/collision_twin.hpp"
#include "model/flat_model.hpp"
#include "passes/collision_detection.hpp"
#include "scene/scene_detail.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec4.hpp>

namespace glcollide {
namespace {

TEST(CollisionLargeBoxGl, BoxesWithThousandsOfFacesLoseNoCandidate) {
    const int cells = 40;
    Scene scene;
    scene.bodies.push_back(detail::generateTetBox({1, 1, 1}, {cells, cells, cells}));
    Body b = detail::generateTetBox({1, 1, 1}, {cells, cells, cells});
    const glm::dmat4 rotate =
        glm::rotate(glm::dmat4(1.0), glm::radians(20.0), glm::normalize(glm::dvec3(1, 1, 1)));
    for (glm::dvec3& p : b.positions)
        p = glm::dvec3(rotate * glm::dvec4(p, 1.0)) + glm::dvec3(1.05, 0.05, 0.0);
    scene.bodies.push_back(std::move(b));
    const model::FlatModel model = model::flatten(scene);

    std::vector<glm::vec4> packed;
    std::vector<glm::vec3> floats;
    for (const glm::dvec3& x : model.positions) {
        floats.emplace_back(static_cast<float>(x.x), static_cast<float>(x.y), static_cast<float>(x.z));
        packed.emplace_back(floats.back(), 1.0f);
    }
    passes::DeviceBuffers buffers;
    buffers.nodeCount = static_cast<std::uint32_t>(packed.size());
    buffers.faceCount = static_cast<std::uint32_t>(model.faceCount());
    buffers.positions = gl::Buffer("positions", packed.size() * sizeof(glm::vec4), packed.data());
    buffers.faces =
        gl::Buffer("faces", model.faceIndices.size() * sizeof(std::uint32_t), model.faceIndices.data());

    passes::CollisionConfig config;
    config.betweenObjects = true;
    config.settings.thickness = 0.01;
    std::vector<std::uint32_t> faceObject;
    for (std::uint32_t o = 0; o < model.objects.size(); ++o)
        faceObject.insert(faceObject.end(), model.objects[o].faceCount, o);
    const std::vector<cpu::FacePair> twin =
        cpu::twinCandidates(model.faceIndices, faceObject, floats, config.settings.thickness, {true, false});
    ASSERT_GT(twin.size(), 1000u) << "the boxes must be in contact";
    for (int depth = 1; depth <= 3; ++depth) {
        config.settings.octreeDepth = depth;
        passes::CollisionDetection detection(config, model);
        detection.detect(buffers, nullptr);
        EXPECT_EQ(detection.readCandidates(), twin) << "octree depth " << depth;
    }
}

} // namespace
} // namespace glcollide
