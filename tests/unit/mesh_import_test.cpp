// Surface import through assimp: welding, the shared cloth and sphere meshes, broken files.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <filesystem>
#include <fstream>
#include <cstdint>
#include <iterator>
#include <string>

using namespace glcollide;
using namespace glcollide::detail;
using ::testing::HasSubstr;

namespace {

const std::string kData = GLCOLLIDE_TEST_DATA_DIR "/mesh/";
// Third-party meshes with their licences and provenance: tests/data/external/README.md.
const std::string kExternal = GLCOLLIDE_TEST_DATA_DIR "/external/";

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

// Vertex/face counts from the upstream descriptions of the DEDO cloths and the IPC sphere.
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
    // OBJ errors name the line (our reader, src/scene/obj_reader.cpp).
    EXPECT_THAT(errorOf(kData + "bad_index.obj"),
                HasSubstr("bad_index.obj:4: face uses vertex 9, but 3 vertices"));
    EXPECT_THAT(errorOf(kData + "inf.obj"),
                HasSubstr("inf.obj:2: vertex 2 coordinate '1e999' is outside double range"));
    EXPECT_THAT(errorOf(kData + "nan.obj"), HasSubstr("nan.obj:2: vertex 2 has a non-finite coordinate"));
    EXPECT_THAT(errorOf(kData + "missing.obj"), HasSubstr("missing.obj: cannot open file"));
}

namespace {

/// Writes `bytes` to glcollide_<name><extension> in the temp folder and returns the import error
/// (or "no error").
std::string errorOfBytes(const std::string& name, const std::string& extension, const std::string& bytes) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("glcollide_" + name + extension);
    std::ofstream(path, std::ios::binary) << bytes;
    const std::string error = errorOf(path.string());
    std::filesystem::remove(path);
    return error;
}

std::string plyErrorOf(const std::string& name, const std::string& text) {
    return errorOfBytes(name, ".ply", text);
}

const std::string kPlyTetraHeader =
    "ply\nformat ascii 1.0\ncomment a tetrahedron\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kPlyTetraBody = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3";

} // namespace

// The strict PLY header check runs before assimp (whose PLY reader hangs on some malformed
// headers: fuzz/regressions/mesh_ply/). Valid files pass; each rule names its header line.
TEST(PlyHeader, ValidAsciiPassesEvenWithoutAFinalNewline) {
    EXPECT_EQ(plyErrorOf("valid", kPlyTetraHeader + kPlyTetraBody), "no error");
    EXPECT_EQ(plyErrorOf("valid_crlf", "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
                                       "property float y\r\nproperty float z\r\nelement face 1\r\n"
                                       "property list uchar int vertex_indices\r\nend_header\r\n"
                                       "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"),
              "no error");
}

TEST(PlyHeader, MalformedHeadersNameTheLine) {
    EXPECT_THAT(plyErrorOf("magic", "PLY\n"), HasSubstr(".ply:1: not a PLY file"));
    EXPECT_THAT(plyErrorOf("no_format", "ply\nelement vertex 1\nend_header\n"),
                HasSubstr(".ply:2: expected the 'format' line"));
    EXPECT_THAT(plyErrorOf("format", "ply\nformat ascii 2.0\nend_header\n"),
                HasSubstr(".ply:2: expected 'format ascii"));
    EXPECT_THAT(plyErrorOf("keyword", "ply\nformat ascii 1.0\nelement vertex 1\nproptex 3\nend_header\n0\n"),
                HasSubstr(".ply:4: unknown PLY header keyword 'proptex'"));
    EXPECT_THAT(
        plyErrorOf("type", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n0\n"),
        HasSubstr(".ply:4: expected 'property <type> <name>'"));
    EXPECT_THAT(
        plyErrorOf("list",
                   "ply\nformat ascii 1.0\nelement face 1\nproperty list float int v\nend_header\n0\n"),
        HasSubstr(".ply:4: expected 'property list <integer type>"));
    EXPECT_THAT(plyErrorOf("orphan", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
                HasSubstr(".ply:3: 'property' before any 'element'"));
    EXPECT_THAT(plyErrorOf("count", "ply\nformat ascii 1.0\nelement vertex -4\nend_header\n"),
                HasSubstr(".ply:3: expected 'element <name> <count>'"));
    EXPECT_THAT(plyErrorOf("unended", "ply\nformat ascii 1.0\nelement vertex 1\n"),
                HasSubstr("no end_header"));
}

TEST(PlyHeader, CountsMustFitInTheFile) {
    // ASCII: one character and a separator per value at least.
    std::string header = kPlyTetraHeader;
    header.replace(header.find("vertex 4"), 8, "vertex 4000000000");
    EXPECT_THAT(plyErrorOf("ascii_count", header + kPlyTetraBody),
                HasSubstr(".ply:4: element 'vertex' declares 4000000000 entries"));
    // Binary: the fixed bytes of each element (the list's count byte for a face).
    const std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n"
                               "property double y\nproperty double z\nelement face 2\n"
                               "property list uchar int vertex_indices\nend_header\n";
    EXPECT_THAT(plyErrorOf("binary_count", binary + std::string(24 + 1, '\0')),
                HasSubstr(".ply:7: element 'face' declares 2 entries, more than the 25 bytes"));
}

namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string glbErrorOf(const std::string& name, const std::string& bytes) {
    return errorOfBytes(name, ".glb", bytes);
}

void putLittleEndian32(std::string& bytes, std::size_t at, std::uint32_t v) {
    for (std::size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((v >> (8 * i)) & 0xFFu);
}

} // namespace

// two_instances.glb is two_instances.gltf in a GLB container (JSON chunk + BIN chunk).
TEST(GlbContainer, ValidFileImportsLikeItsGltf) {
    const SurfaceMesh glb = importSurfaceMesh(kData + "two_instances.glb");
    const SurfaceMesh gltf = importSurfaceMesh(kData + "two_instances.gltf");
    EXPECT_EQ(glb.faces, gltf.faces);
    EXPECT_EQ(glb.positions, gltf.positions);
}

TEST(GlbContainer, BrokenContainersNameTheByte) {
    const std::string good = readBytes(kData + "two_instances.glb");
    ASSERT_GT(good.size(), 28u);
    EXPECT_THAT(glbErrorOf("short", good.substr(0, 8)),
                HasSubstr(".glb: byte 0: a GLB file starts with a 12-byte header"));
    std::string magic = good;
    magic[0] = 'x';
    EXPECT_THAT(glbErrorOf("magic", magic), HasSubstr(".glb: byte 0: not a GLB file"));
    std::string version = good;
    putLittleEndian32(version, 4, 1);
    EXPECT_THAT(glbErrorOf("version", version), HasSubstr(".glb: byte 4: GLB version 1 (expected 2"));
    EXPECT_THAT(glbErrorOf("truncated", good.substr(0, good.size() - 4)),
                HasSubstr(".glb: byte 8: the header's length"));
    std::string chunk = good;
    putLittleEndian32(chunk, 12, 0xEC000001u); // the fuzzer's input: assimp allocated this much
    EXPECT_THAT(glbErrorOf("chunk", chunk),
                HasSubstr(".glb: byte 12: JSON chunk of 3959422977 bytes runs past the end"));
}

// PLY bodies (our reader, src/scene/ply_reader.cpp): the three encodings give the same mesh, and
// every count or index from the file is checked before use.
TEST(PlyBody, AsciiAndBothBinaryEncodingsReadTheSameTetrahedron) {
    const std::string corpus = GLCOLLIDE_SOURCE_DIR "/fuzz/corpus/mesh_ply/";
    const SurfaceMesh ascii = importSurfaceMesh(corpus + "tetra_ascii.ply");
    const SurfaceMesh little = importSurfaceMesh(corpus + "tetra_binary.ply"); // doubles
    const SurfaceMesh big = importSurfaceMesh(corpus + "tetra_binary_be.ply"); // big-endian floats
    ASSERT_EQ(ascii.faces.size(), 4u);
    EXPECT_EQ(ascii.positions.size(), 4u);
    EXPECT_EQ(little.faces, ascii.faces);
    EXPECT_EQ(little.positions, ascii.positions);
    EXPECT_EQ(big.faces, ascii.faces);
    EXPECT_EQ(big.positions, ascii.positions);
}

TEST(PlyBody, PolygonsAreSplitIntoFansAndShortListsIgnored) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n2 0 1\n";
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "glcollide_quad.ply";
    std::ofstream(path, std::ios::binary) << text;
    const SurfaceMesh m = importSurfaceMesh(path.string());
    std::filesystem::remove(path);
    ASSERT_EQ(m.faces.size(), 2u);
    EXPECT_EQ(m.faces[0], (Face{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Face{0, 2, 3}));
}

TEST(PlyBody, BadBodiesNameTheLineOrByte) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_THAT(plyErrorOf("index", header + vertices + "3 0 1 3\n"),
                HasSubstr(".ply:13: face 0 uses vertex 3 of 3"));
    EXPECT_THAT(plyErrorOf("negative", header + vertices + "3 0 -1 2\n"),
                HasSubstr(".ply:13: face 0 uses vertex -1 of 3"));
    EXPECT_THAT(
        plyErrorOf("list_length", header + vertices + "255 0 1 2\n"),
        HasSubstr(
            ".ply:13: list 'vertex_indices' of face 0 has 255 entries, more than the rest of the file"));
    EXPECT_THAT(plyErrorOf("uchar_range", header + vertices + "256 0 1 2\n"),
                HasSubstr("256 is outside its PLY type's range"));
    EXPECT_THAT(plyErrorOf("float_index", header + vertices + "3 0 1.5 2\n"),
                HasSubstr(".ply:13: expected an integer entry"));
    EXPECT_THAT(plyErrorOf("nan", header + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
                HasSubstr("vertex 1 has a non-finite coordinate"));
    EXPECT_THAT(plyErrorOf("huge", header + "0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n"),
                HasSubstr(".ply:11: property 'x' of vertex 1 '1e999' is outside double range"));
    EXPECT_THAT(
        plyErrorOf("no_xyz", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n"),
        HasSubstr(".ply:3: element 'vertex' needs properties x, y and z"));
    const std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
    EXPECT_THAT(
        plyErrorOf("binary_truncated", binary + std::string(12, '\0') + "\x03" + std::string(4, '\0')),
        HasSubstr(": byte "));
}

// OBJ statements beyond plain triangles: index forms, negative indices, polygons, continuation
// lines, and the statements that carry no surface.
TEST(ObjReader, IndexFormsPolygonsAndIgnoredStatements) {
    const std::string text =
        "mtllib x.mtl\no quad\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\n"
        "v 0 1 0\ng g1\ns off\nusemtl m\nf 1/1/1 2//1 \\\n -2/1 -1\nl 1 3\np 2\nv 5 5 5\n";
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "glcollide_quad.obj";
    std::ofstream(path, std::ios::binary) << text;
    const SurfaceMesh m = importSurfaceMesh(path.string());
    std::filesystem::remove(path);
    ASSERT_EQ(m.faces.size(), 2u); // the quad as a fan
    EXPECT_EQ(m.faces[0], (Face{0, 1, 2}));
    EXPECT_EQ(m.faces[1], (Face{0, 2, 3}));
    EXPECT_EQ(m.positions.size(), 4u); // the stray vertex (5, 5, 5) is not a node
}

TEST(ObjReader, BadStatementsNameTheLine) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const auto objErrorOf = [](const std::string& name, const std::string& text) {
        return errorOfBytes(name, ".obj", text);
    };
    EXPECT_THAT(objErrorOf("zero", v + "f 0 1 2\n"), HasSubstr(".obj:4: expected a vertex index"));
    EXPECT_THAT(objErrorOf("two", v + "f 1 2\n"),
                HasSubstr(".obj:4: a face needs at least 3 vertices, got 2"));
    EXPECT_THAT(objErrorOf("negative", v + "f -1 -2 -4\n"),
                HasSubstr(".obj:4: face uses vertex -4, but 3 vertices"));
    EXPECT_THAT(objErrorOf("forward", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n"),
                HasSubstr(".obj:2: face uses vertex 2, but 1 vertices"));
    EXPECT_THAT(objErrorOf("short_v", "v 0 0\n"), HasSubstr(".obj:1: expected 'v x y z'"));
    EXPECT_THAT(objErrorOf("text", "v 0 zero 0\n"),
                HasSubstr(".obj:1: expected a number as vertex coordinate, got 'zero'"));
    EXPECT_THAT(objErrorOf("curve", v + "cstype bspline\n"),
                HasSubstr(".obj:4: free-form geometry ('cstype') is not supported"));
    EXPECT_THAT(objErrorOf("empty", "# nothing\n"), HasSubstr(": the file contains no mesh"));
    EXPECT_THAT(objErrorOf("points", v + "p 1 2 3\n"), HasSubstr(": the mesh has no triangles"));
}

// Duplicated faces (either winding) and zero-area faces are modelling errors, named by line where
// the format has lines and by triangle otherwise.
TEST(SurfaceChecks, DuplicatedAndZeroAreaFacesAreErrors) {
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    EXPECT_THAT(
        errorOfBytes("dup", ".obj", v + "f 1 2 3\nf 1 2 4\nf 3 2 1\n"),
        HasSubstr(".obj:7: face uses the same three vertices as the face of line 5 (a duplicated face)"));
    EXPECT_THAT(errorOfBytes("flat", ".obj", v + "v 2 0 0\nf 1 2 3\nf 1 2 5\n"),
                HasSubstr(".obj:7: face has zero area (its three vertices are collinear)"));
    const std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 2\n"
                               "property list uchar int vertex_indices\nend_header\n";
    std::string body;
    for (const float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
        body.append(reinterpret_cast<const char*>(&f), 4);
    for (int face = 0; face < 2; ++face) {
        body += '\x03';
        for (const int i : {0, 1, 2}) body.append(reinterpret_cast<const char*>(&i), 4);
    }
    EXPECT_THAT(errorOfBytes("dup_binary", ".ply", binary + body),
                HasSubstr(".ply: triangle 1 uses the same three vertices as triangle 0 (a duplicated face)"));
}

// A leading '+' (accepted by strtod and written by some exporters) reads as the number.
TEST(ObjReader, LeadingPlusSignsAreNumbers) {
    EXPECT_EQ(errorOfBytes("plus", ".obj", "v +0 0 0\nv +1.0 0 0\nv 0 +.5e1 0\nf 1 2 3\n"), "no error");
    EXPECT_THAT(errorOfBytes("plus_plus", ".obj", "v ++1 0 0\n"), HasSubstr(".obj:1: expected a number"));
    EXPECT_EQ(
        plyErrorOf("plus",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                   "+0 0 0\n1 0 0\n0 +1 0\n+3 0 1 +2\n"),
        "no error");
}
