// Gmsh MSH reader: hand-made files with known answers, broken files, and the IPC tet meshes.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <string>

using namespace glcollide;
using namespace glcollide::detail;
using ::testing::HasSubstr;

namespace {

const std::string kData = GLCOLLIDE_TEST_DATA_DIR "/mesh/";
// Copies of the IPC meshes with their licence and provenance: tests/data/external/README.md.
const std::string kIpc = GLCOLLIDE_TEST_DATA_DIR "/external/ipc-sim-meshes/tetMeshes/";

double tetVolumeSum(const TetMesh& m) {
    double v = 0.0;
    for (const Tet& t : m.tets)
        v += tetDet(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], m.positions[t[3]]) / 6.0;
    return v;
}

/// Volume enclosed by a closed triangle surface (divergence theorem); positive when wound outward.
double enclosedVolume(const std::vector<glm::dvec3>& p, const std::vector<Face>& faces) {
    double v = 0.0;
    for (const Face& f : faces) v += glm::dot(p[f[0]], glm::cross(p[f[1]], p[f[2]])) / 6.0;
    return v;
}

std::string errorOf(const std::string& file) {
    try {
        readGmsh(kData + file);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(GmshReader, Reads41WithSparseTagsBlocksAndSkippedSections) {
    const TetMesh m = readGmsh(kData + "two_tets_v41.msh");
    ASSERT_EQ(m.positions.size(), 5u);
    ASSERT_EQ(m.tets.size(), 2u); // the triangle element block is ignored
    EXPECT_EQ(m.positions[4], glm::dvec3(1, 1, 1));
    EXPECT_EQ(m.tetLines, (std::vector<std::size_t>{28, 29}));
    // The second tet is written inverted; the reader swaps its last two nodes.
    for (const Tet& t : m.tets)
        EXPECT_GT(tetDet(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], m.positions[t[3]]), 0.0);
    // Exact: volumes 1/6 and 2/6 of small-integer coordinates, sums exact to one rounding.
    EXPECT_NEAR(tetVolumeSum(m), 0.5, 1e-15);
    const auto faces = boundaryFaces(m.tets, "two tets");
    EXPECT_EQ(faces.size(), 6u);
    EXPECT_NEAR(enclosedVolume(m.positions, faces), 0.5, 1e-15);
}

TEST(GmshReader, Reads22SameAs41) {
    const TetMesh a = readGmsh(kData + "two_tets_v22.msh");
    const TetMesh b = readGmsh(kData + "two_tets_v41.msh");
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.tetLines, (std::vector<std::size_t>{15, 16}));
}

TEST(GmshReader, ErrorsNameFileAndLine) {
    EXPECT_THAT(errorOf("bad_tag_v41.msh"), HasSubstr("bad_tag_v41.msh:29: node tag 77 is not defined"));
    EXPECT_THAT(errorOf("bad_number_v41.msh"), HasSubstr("bad_number_v41.msh:15: expected a number"));
    EXPECT_THAT(errorOf("truncated_v41.msh"), HasSubstr("truncated_v41.msh:21: unexpected end of file"));
    EXPECT_THAT(errorOf("binary_v41.msh"), HasSubstr("binary_v41.msh:2: binary MSH files are not supported"));
    EXPECT_THAT(errorOf("tet10_v41.msh"), HasSubstr("tet10_v41.msh:27: 10-node"));
    EXPECT_THAT(errorOf("version3.msh"), HasSubstr("version3.msh:2: MSH version 3.0 is not supported"));
    EXPECT_THAT(errorOf("repeated_node_v22.msh"),
                HasSubstr("repeated_node_v22.msh:16: tetrahedron repeats node"));
    EXPECT_THAT(errorOf("flat_v22.msh"), HasSubstr("flat_v22.msh:13: degenerate"));
    EXPECT_THAT(errorOf("does_not_exist.msh"), HasSubstr("does_not_exist.msh: cannot open file"));
    EXPECT_THAT(errorOf("two_tets0.node"), HasSubstr("two_tets0.node:1: "));
}

struct IpcMesh {
    const char* file;
    std::size_t nodes, tets, surface;
};

class GmshIpcMeshes : public ::testing::TestWithParam<IpcMesh> {};

// Counts from the IPC mesh descriptions (see tests/data/external/README.md).
INSTANTIATE_TEST_SUITE_P(
    GmshIpc, GmshIpcMeshes,
    ::testing::Values(IpcMesh{"tet.msh", 4, 1, 4}, IpcMesh{"tet-pyramid.msh", 4, 1, 4},
                      IpcMesh{"tet-perp-edges.msh", 4, 1, 4}, IpcMesh{"cube.msh", 8, 6, 12},
                      IpcMesh{"erleben/spike.msh", 5, 2, 6}, IpcMesh{"erleben/wedge.msh", 6, 3, 8},
                      IpcMesh{"torus.msh", 200, 491, 400}, IpcMesh{"mat20x20.msh", 800, 2166, 1596},
                      IpcMesh{"mat40x40.msh", 3200, 9126, 6396}, IpcMesh{"sphere1K.msh", 1760, 6851, 2474},
                      IpcMesh{"cow_head.msh", 1328, 5029, 1986}, IpcMesh{"bunny.msh", 4670, 19379, 6266},
                      IpcMesh{"Armadillo13K.msh", 13230, 54985, 17296}));

TEST_P(GmshIpcMeshes, CountsAndOutwardBoundary) {
    const IpcMesh& want = GetParam();
    const TetMesh m = readGmsh(kIpc + want.file);
    EXPECT_EQ(m.positions.size(), want.nodes);
    EXPECT_EQ(m.tets.size(), want.tets);
    const auto faces = boundaryFaces(m.tets, want.file);
    EXPECT_EQ(faces.size(), want.surface);
    const double tetVolume = tetVolumeSum(m);
    EXPECT_GT(tetVolume, 0.0);
    // Both sums add up to ~1e5 terms of similar size: agree to ~1e-12 relative in double.
    EXPECT_NEAR(enclosedVolume(m.positions, faces), tetVolume, 1e-9 * tetVolume);
}
