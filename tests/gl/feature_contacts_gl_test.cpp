// Engine::readFeaturePairs and Engine::readContacts (issue 25: the viewer's contact-pair overlay):
// the device's feature-pair lists against the CPU twin of the Representative-Triangle expansion
// (cpu::featurePairs) of the same candidates, and a hand-built contact: one vertex resting 4 mm
// above a triangle, inside a 10 mm thickness, is exactly one vertex-face contact with that vertex
// and that face, its depth, normal and weights worked out by hand.

#include "cpu/contact_twin.hpp"
#include "model/features.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace glcollide {
namespace {

// Two cloths 5 mm apart, the upper one falling onto the lower (as in step_substep_gl_test.cpp).
const char* kTwoCloths = R"({"format_version": 1, "name": "two cloths", "effects":
    ["gravity", "springs", "collisions", "self_collisions"],
  "time": {"dt": 0.01, "substeps": 4},
  "collision": {"broad_phase": "bvh", "response": "bridson", "thickness": 0.01, "stiffness": 100},
  "objects": [
    {"name": "below", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [6, 6]},
     "mass": 0.2, "springs": {"stiffness": 200}, "pinned": [0, 1, 2]},
    {"name": "above", "generator": {"type": "cloth", "size": [0.3, 0.3], "resolution": [5, 5]},
     "transform": {"translate": [0.02, 0.005, 0.01]}, "velocity": [0, -0.2, 0],
     "mass": 0.1, "springs": {"stiffness": 200}}]})";

std::vector<std::uint32_t> readFaces(const Engine& engine) {
    std::vector<std::uint32_t> faces(3 * std::size_t{engine.faceCount()});
    glGetNamedBufferSubData(engine.faceIndexBuffer(), 0, static_cast<GLsizeiptr>(faces.size() * 4),
                            faces.data());
    return faces;
}

TEST(FeatureContactsGl, FeaturePairsAreTheTwinsExpansionOfTheCandidates) {
    Engine engine(parseScene(kTwoCloths, ".", "feature pairs"), {false});
    std::size_t checked = 0;
    for (int frame = 0; frame < 4; ++frame) {
        engine.step();
        engine.detectCollisions(); // the lists of the positions readPositions() returns
        const std::vector<std::array<std::uint32_t, 2>> candidates = engine.readCandidatePairs();
        const std::vector<std::uint32_t> faces = readFaces(engine);
        const cpu::FeaturePairList want = cpu::featurePairs(faces, model::ownedFeatures(faces), candidates);
        const FeaturePairs got = engine.readFeaturePairs();
        EXPECT_EQ(got.vertexFace, want.vertexFace) << "frame " << frame;
        EXPECT_EQ(got.edgeEdge, want.edgeEdge) << "frame " << frame;
        checked += got.vertexFace.size() + got.edgeEdge.size();
        // Every contact is among the pairs, and within the thickness (depth in (0, thickness]).
        for (const FeatureContact& c : engine.readContacts()) {
            EXPECT_GT(c.depth, 0.0);
            EXPECT_LE(c.depth, 0.01);
        }
    }
    EXPECT_GT(checked, 0u) << "no feature pair: the comparison tested nothing";
}

TEST(FeatureContactsGl, AVertexRestingOnATriangleIsExactlyOneVertexFaceContact) {
    // Triangle A: (0,0,0), (1,0,0), (0,0,1) in the plane y = 0 (an open surface: both of its sides
    // take contacts). Triangle B: its first corner 4 mm above A's point (0.25, 0, 0.25), the others
    // 0.5 m up, so no other vertex, and no edge, comes within the 10 mm of the other triangle.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("glcollide-contact-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream a(dir / "a.obj");
        a << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n";
        std::ofstream b(dir / "b.obj");
        b << "v 0.25 0.004 0.25\nv 0.35 0.5 0.25\nv 0.25 0.5 0.35\nf 1 2 3\n";
    }
    const std::string json = R"({"format_version": 1, "name": "resting vertex", "effects": ["collisions"],
      "time": {"dt": 0.01, "substeps": 1},
      "collision": {"broad_phase": "bvh", "response": "bridson", "thickness": 0.01, "stiffness": 100},
      "objects": [{"name": "a", "mesh": "a.obj", "mass": 1.0}, {"name": "b", "mesh": "b.obj", "mass": 1.0}]})";
    Engine engine(parseScene(json, dir, "resting vertex"), {false});
    std::filesystem::remove_all(dir);
    ASSERT_EQ(engine.faceCount(), 2u);
    engine.detectCollisions();
    const std::uint32_t vertex = engine.bodyFirstNodes()[1]; // b's first node
    const std::vector<std::uint32_t> faces = readFaces(engine);
    const std::vector<FeatureContact> contacts = engine.readContacts();
    ASSERT_EQ(contacts.size(), 1u);
    const FeatureContact& c = contacts[0];
    EXPECT_FALSE(c.edgeEdge);
    EXPECT_EQ(c.nodes[0], vertex);
    EXPECT_EQ((std::array<std::uint32_t, 3>{c.nodes[1], c.nodes[2], c.nodes[3]}),
              (std::array<std::uint32_t, 3>{faces[0], faces[1], faces[2]}))
        << "face 0, a's only face";
    // Positions are stored as floats: coordinates of magnitude <= 1 are off by at most 2^-24 each,
    // so the distance (and depth) and the barycentric weights are off by a few 2^-24; 1e-6 bounds them.
    const double tol = 1e-6;
    EXPECT_NEAR(c.depth, 0.01 - 0.004, tol);
    EXPECT_NEAR(std::abs(c.normal.y), 1.0, tol); // perpendicular to A
    EXPECT_GT(c.normal.y, 0.0) << "from the face (side B) to the vertex above it (side A)";
    EXPECT_EQ(c.weights[0], 1.0);
    // (0.25, 0.25) in A = (0,0,0) + s·(1,0,0) + t·(0,0,1): weights 1 − s − t, s, t of the
    // corners in a.obj's order, which the face (1 3 2) visits as corners 0, 2, 1.
    std::array<double, 3> byCorner{};
    for (int k = 0; k < 3; ++k) byCorner[faces[k]] = -c.weights[1 + k];
    EXPECT_NEAR(byCorner[0], 0.5, tol);
    EXPECT_NEAR(byCorner[1], 0.25, tol);
    EXPECT_NEAR(byCorner[2], 0.25, tol);
}

TEST(FeatureContactsGl, ASceneWithoutCollisionsIsAnError) {
    Engine engine(parseScene(R"({"format_version": 1, "name": "free", "effects": ["gravity"],
      "time": {"dt": 0.01, "substeps": 1},
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [3, 3]},
                   "mass": 0.5}]})",
                             ".", "free"),
                  {false});
    EXPECT_THROW((void)engine.readFeaturePairs(), Error);
    EXPECT_THROW((void)engine.readContacts(), Error);
}

} // namespace
} // namespace glcollide
