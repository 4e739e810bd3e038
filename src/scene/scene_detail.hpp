#pragma once
/// \file Internals of the scene module: mesh readers, generators, springs, boundary extraction and
/// mass lumping. Not part of the public API; the unit tests use it directly.

#include <glcollide/scene.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glcollide::detail {

using Face = std::array<std::uint32_t, 3>;
using Tet = std::array<std::uint32_t, 4>;

/// A triangle surface as imported: positions in the file's units (metres assumed).
struct SurfaceMesh {
    std::vector<glm::dvec3> positions;
    std::vector<Face> faces;
};

/// A tetrahedral mesh as read: every tet has positive volume after reading (see orientTets).
struct TetMesh {
    std::vector<glm::dvec3> positions;
    std::vector<Tet> tets;
    /// 1-based source line of each tet (for error messages); may be empty for generated meshes.
    std::vector<std::size_t> tetLines;
};

// ---- readers (each throws glcollide::Error naming the file, and the line where there is one) ----

/// OBJ (readObj), PLY (readPly), glTF or GLB (through assimp): all meshes of the file merged, node
/// transforms applied, exactly equal positions welded, point and line primitives ignored.
SurfaceMesh importSurfaceMesh(const std::filesystem::path& path);

/// Wavefront OBJ by our own reader: v and f statements (any index form, negative indices,
/// polygons split into fans); errors name the file and line. Then weldSurface.
SurfaceMesh readObj(const std::filesystem::path& path);

/// PLY (ASCII, binary little/big-endian) by our own reader: vertex x, y, z and face
/// vertex_indices, polygons split into fans; then weldSurface. Errors name the file and the line
/// (ASCII, header) or byte offset (binary).
SurfaceMesh readPly(const std::filesystem::path& path);

/// A PLY file's vertices and faces as stored, before welding: vertex i is the file's vertex i
/// (positions exact: every PLY float or double is a double), polygons split into fans, each
/// triangle with the index of the face element it came from (faceElement) and, for ASCII files,
/// its line (faceLines; empty for binary files). faceElements: how many face elements were read
/// (faces.size() equals it exactly when every face is a triangle).
struct PlyMesh {
    std::vector<glm::dvec3> positions;
    std::vector<Face> faces;
    std::vector<std::uint64_t> faceElement;
    std::vector<std::size_t> faceLines;
    std::uint64_t faceElements = 0;
};

/// The PLY reader of readPly without weldSurface: for data whose vertex and face numbering
/// matters (the CCD query sets name primitives by index). Same errors as readPly's reading.
PlyMesh readPlyAsStored(const std::filesystem::path& path);

/// Welds exactly equal positions (+0 = -0), drops faces that welding collapsed and positions no
/// face uses (keeping the order of first appearance). Throws Error naming `file` (and the face's
/// source line from `faceLines`, when given) for a non-finite position, a zero-area face (three
/// collinear vertices), a duplicated face (the same three vertices, either winding) or when no
/// triangle is left. Shared by the readers of surface meshes.
SurfaceMesh weldSurface(std::vector<glm::dvec3> positions, const std::vector<Face>& faces,
                        const std::string& file, const std::vector<std::size_t>& faceLines = {});

/// Checks a GLB container (header, version 2, length, chunk lengths within the file) before
/// assimp reads it; throws Error naming the file and byte offset. Called for `.glb` files.
void checkGlbContainer(const std::filesystem::path& path);

/// Checks that a `.gltf` file is valid JSON with an object at the top before assimp reads it;
/// throws Error with nlohmann-json's line and column. (GLB: checkGlbContainer checks its chunk.)
void checkGltfJson(const std::filesystem::path& path);

/// Gmsh MSH 4.1 or 2.2 ASCII: 4-node tetrahedra (type 4); other element types and unknown
/// sections (IPC's `$Surface` included) are skipped. Node tags may be sparse.
TetMesh readGmsh(const std::filesystem::path& path);

/// TetGen `.node` + `.ele` (same stem; any `.face` is ignored). 0- or 1-based indices, inferred
/// from the first point index.
TetMesh readTetGen(const std::filesystem::path& nodePath);

// ---- tet topology (tet_surface.cpp) ----

/// 6 × signed volume of (a, b, c, d): det(b − a, c − a, d − a). m³.
double tetDet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);

/// Makes every tet positively oriented by swapping its last two nodes where its volume is
/// negative. Throws for a repeated node, an index out of range or a degenerate (flat) tet,
/// naming `file` and the tet's line from mesh.tetLines when available.
void orientTets(TetMesh& mesh, const std::string& file);

/// The triangles used by exactly one tet, wound counter-clockwise seen from outside (tets must
/// be positively oriented). Order: by tet, then by face. Throws if a triangle is shared by more
/// than two tets (non-manifold), naming `what`.
std::vector<Face> boundaryFaces(const std::vector<Tet>& tets, const std::string& what);

// ---- springs (springs.cpp); rest length, stiffness and damping are filled in later ----

/// One spring per unique edge of the triangles, sorted by (min index, max index).
std::vector<Spring> surfaceEdgeSprings(const std::vector<Face>& faces, SpringKind kind);
/// One spring per unique edge of the tets, sorted by (min index, max index).
std::vector<Spring> tetEdgeSprings(const std::vector<Tet>& tets);
/// Across every interior edge (shared by exactly two triangles) a spring between the two opposite
/// vertices; pairs that are already an edge, or already produced, are skipped.
std::vector<Spring> surfaceBendSprings(const std::vector<Face>& faces);
/// restLength = current distance between the ends, for every spring of the body.
void setRestLengths(Body& body);

// ---- generators (generators.cpp): geometry and springs with their kinds, local frame ----

/// `nx` × `ny` nodes spanning `width` × `height` m in the local XY plane, centred at the origin.
/// Node (i, j) has index j·nx + i; row j = 0 is the top (y = +height/2), i = 0 the left (x < 0).
/// Faces face +Z. Springs: Structural, Shear (both diagonals) and, if `withBend`, Bend (two
/// nodes apart along rows and columns).
Body generateCloth(double width, double height, int nx, int ny, bool withShear, bool withBend);

/// A tube (a sleeve: a cylinder without caps) of `radius` m around the local Y axis, `length` m long
/// and centred at the origin: `along` rings of `around` nodes, ring j = 0 at the top (y = +length/2);
/// node (i, j) has index j·around + i, node i of a ring at angle 2πi/around from +X towards +Z.
/// Faces face away from the axis; two boundary loops (the rings at both ends). No springs: the
/// scene gives it a surface's edge and bend springs, as for a surface mesh.
/// `bendDegrees` in [0, 180) bends the middle third of the axis into a circular arc turning from −Y
/// towards +X (an elbow); the top third stays where the straight tube's is, the rings stay
/// perpendicular to the axis, and `length` is measured along it. 0: the straight tube above.
Body generateTube(double radius, double length, int around, int along, double bendDegrees = 0.0);

/// A box of `size` m centred at the origin, `cells` cubes per axis, each split into 6 tets along
/// its main diagonal (the Freudenthal split, conforming between neighbour cells). Springs: unique
/// tet edges; faces: the boundary.
Body generateTetBox(const glm::dvec3& size, const std::array<int, 3>& cells);

/// A tetrahedral ball whose surface is the icosphere of `radius` m with `subdivisions` refinements
/// (surface nodes first, in icosphere order); inside, one icosphere shell per coarser level joined
/// by 7-tet transition cells, and a centre node (the last index). Valence at most 19, node count
/// about 1.33 × the surface's. Springs: unique tet edges. Faces: the icosphere surface, outward.
Body generateSphere(double radius, int subdivisions);

// ---- mass (mass.cpp) ----

/// Lumped measure per node: area/3 of each triangle (when `tets` is empty) or volume/4 of each
/// tet, in m² or m³. Throws if a node receives nothing or the total is zero, naming `what`.
std::vector<double> lumpedMeasure(const std::vector<glm::dvec3>& positions, const std::vector<Face>& faces,
                                  const std::vector<Tet>& tets, const std::string& what);

} // namespace glcollide::detail
