// Surface import through assimp: welding, the shared cloth and sphere meshes, broken files.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <string>

using namespace glcollide;
using namespace glcollide::detail;
using ::testing::HasSubstr;

namespace {

const std::string kData = GLCOLLIDE_TEST_DATA_DIR "/mesh/";
const std::string kExternal = GLCOLLIDE_SOURCE_DIR "/../shared/external/";

std::string errorOf(const std::string& path) {
    try {
        importSurfaceMesh(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(MeshImport, WeldsSeamsAndDuplicatePositions) {
    const SurfaceMesh m = importSurfaceMesh(kData + "seam_square.obj");
    EXPECT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.faces.size(), 2u);
    // The two triangles share the diagonal after welding.
    EXPECT_EQ(surfaceEdgeSprings(m.faces, SpringKind::Edge).size(), 5u);
}

// Vertex/face counts from the READMEs of external/dedo-cloth-with-holes and ipc-sim-meshes.
TEST(MeshImport, DedoClothsKeepOneVertexPerPosition) {
    const SurfaceMesh button = importSurfaceMesh(kExternal + "dedo-cloth-with-holes/button_cloth.obj");
    EXPECT_EQ(button.positions.size(), 392u);
    EXPECT_EQ(button.faces.size(), 686u);
    const SurfaceMesh mask = importSurfaceMesh(kExternal + "dedo-cloth-with-holes/mask_0.obj");
    EXPECT_EQ(mask.positions.size(), 401u);
    EXPECT_EQ(mask.faces.size(), 628u);
}

TEST(MeshImport, IpcSphere) {
    const SurfaceMesh s = importSurfaceMesh(kExternal + "ipc-sim-meshes/triMeshes/sphere1K.obj");
    EXPECT_EQ(s.positions.size(), 1239u);
    EXPECT_EQ(s.faces.size(), 2474u);
}

TEST(MeshImport, BinaryPly) {
    // thick-cloth/t0.ply: binary little-endian doubles, 233 vertices / 404 faces (README).
    const SurfaceMesh s = importSurfaceMesh(kExternal + "ipc-toolkit-tests-data/thick-cloth/t0.ply");
    EXPECT_EQ(s.positions.size(), 233u);
    EXPECT_EQ(s.faces.size(), 404u);
}

TEST(MeshImport, GltfNodeTransformsAndMergedInstances) {
    // One triangle (0,0,0) (1,0,0) (0,1,0) instanced by two nodes, the second moved by +1 in x:
    // the instances share the position (1,0,0), which the weld joins.
    const SurfaceMesh m = importSurfaceMesh(kData + "two_instances.gltf");
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.positions.size(), 5u);
    glm::dvec3 hi(-1e9);
    for (const auto& p : m.positions) hi = glm::max(hi, p);
    EXPECT_EQ(hi, glm::dvec3(2, 1, 0));
}

TEST(MeshImport, BrokenFilesNameTheFile) {
    EXPECT_THAT(errorOf(kData + "empty.obj"), HasSubstr("empty.obj: "));
    EXPECT_THAT(errorOf(kData + "bad_index.obj"), HasSubstr("bad_index.obj: "));
    EXPECT_THAT(errorOf(kData + "inf.obj"), HasSubstr("inf.obj: "));
    EXPECT_THAT(errorOf(kData + "nan.obj"), HasSubstr("nan.obj: "));
    EXPECT_THAT(errorOf(kData + "missing.obj"), HasSubstr("missing.obj: cannot open file"));
}
