// Surface mesh import: glTF and GLB through assimp, OBJ and PLY by obj_reader.cpp and
// ply_reader.cpp; welding.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <tuple>

namespace glcollide::detail {
namespace {

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
                std::vector<glm::dvec3>& positions, std::vector<Face>& faces, const std::string& file) {
    const aiMatrix4x4 world = parent * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
        const auto offset = static_cast<std::uint32_t>(positions.size());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D p = world * mesh.mVertices[v];
            positions.emplace_back(p.x, p.y, p.z);
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) continue; // points and lines carry no surface
            Face out{};
            for (unsigned k = 0; k < 3; ++k) {
                if (face.mIndices[k] >= mesh.mNumVertices)
                    throw Error(file + ": mesh '" + mesh.mName.C_Str() + "' face " + std::to_string(f) +
                                " uses vertex " + std::to_string(face.mIndices[k]) + " of " +
                                std::to_string(mesh.mNumVertices));
                out[k] = offset + face.mIndices[k];
            }
            faces.push_back(out);
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        appendNode(scene, *node.mChildren[c], world, positions, faces, file);
}

} // namespace

SurfaceMesh importSurfaceMesh(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(file + ": cannot open file");
    std::string extension = path.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == ".ply") return readPly(path);
    if (extension == ".obj") return readObj(path);
    if (extension == ".glb") checkGlbContainer(path);
    if (extension == ".gltf") checkGltfJson(path);

    Assimp::Importer importer;
    // Simulation meshes need one node per position: drop every attribute that makes assimp split
    // vertices at seams (normals, UVs, tangents, colours).
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                                aiComponent_NORMALS | aiComponent_TEXCOORDS |
                                    aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                                    aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS | aiComponent_TEXTURES |
                                    aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS);
    // Read first, post-process after validating: without aiProcess_ValidateDataStructure a face
    // index beyond the vertex count (a fuzzed PLY, when assimp still read PLY) crashed its post-processing.
    const aiScene* read = importer.ReadFile(file, 0);
    if (read == nullptr) throw Error(file + ": cannot import mesh: " + importer.GetErrorString());
    if (read->mRootNode == nullptr || read->mNumMeshes == 0)
        throw Error(file + ": the file contains no mesh");
    bool anyPolygon = false;
    for (unsigned m = 0; m < read->mNumMeshes && !anyPolygon; ++m)
        for (unsigned f = 0; f < read->mMeshes[m]->mNumFaces && !anyPolygon; ++f)
            anyPolygon = read->mMeshes[m]->mFaces[f].mNumIndices >= 3;
    if (!anyPolygon) throw Error(file + ": the mesh has no triangles");
    const aiScene* scene =
        importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_RemoveComponent |
                                     aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (scene == nullptr) throw Error(file + ": cannot import mesh: " + importer.GetErrorString());

    std::vector<glm::dvec3> raw;
    std::vector<Face> rawFaces;
    appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), raw, rawFaces, file);
    return weldSurface(std::move(raw), rawFaces, file);
}

SurfaceMesh weldSurface(std::vector<glm::dvec3> raw, const std::vector<Face>& rawFaces,
                        const std::string& file, const std::vector<std::size_t>& faceLines) {
    // Where a triangle came from, for messages: "file:line: face" or "file: triangle k".
    const auto where = [&](std::size_t f) {
        return f < faceLines.size() && faceLines[f] != 0
                   ? file + ":" + std::to_string(faceLines[f]) + ": face"
                   : file + ": triangle " + std::to_string(f);
    };
    for (std::size_t v = 0; v < raw.size(); ++v)
        if (!std::isfinite(raw[v].x) || !std::isfinite(raw[v].y) || !std::isfinite(raw[v].z))
            throw Error(file + ": vertex " + std::to_string(v) + " has a non-finite coordinate");

    // assimp's JoinIdenticalVertices compares whole vertices per mesh; weld again on position
    // alone and across meshes so seams and mesh boundaries do not cut the cloth apart.
    SurfaceMesh out;
    std::map<std::tuple<double, double, double>, std::uint32_t> welded;
    std::vector<std::uint32_t> remap(raw.size());
    for (std::size_t v = 0; v < raw.size(); ++v) {
        // +0.0 and -0.0 compare equal; normalise so the map treats them as one key.
        const auto key = std::make_tuple(raw[v].x + 0.0, raw[v].y + 0.0, raw[v].z + 0.0);
        auto [it, inserted] = welded.emplace(key, static_cast<std::uint32_t>(out.positions.size()));
        if (inserted) out.positions.push_back(raw[v]);
        remap[v] = it->second;
    }
    std::map<std::array<std::uint32_t, 3>, std::size_t> seen; // sorted vertices -> first raw face
    for (std::size_t r = 0; r < rawFaces.size(); ++r) {
        const Face& f = rawFaces[r];
        const Face g{remap[f[0]], remap[f[1]], remap[f[2]]};
        // A triangle that welding collapsed to an edge has no area and no orientation.
        if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) continue;
        // Three distinct but collinear positions: no normal, no area, no mass; a modelling error.
        const glm::dvec3 &a = out.positions[g[0]], &b = out.positions[g[1]], &c = out.positions[g[2]];
        if (glm::cross(b - a, c - a) == glm::dvec3(0.0))
            throw Error(where(r) + " has zero area (its three vertices are collinear)");
        // The same three vertices twice (either winding) would double the mass there and make a
        // face collide with its copy.
        std::array<std::uint32_t, 3> key = g;
        std::sort(key.begin(), key.end());
        if (const auto [it, inserted] = seen.emplace(key, r); !inserted)
            throw Error(where(r) + " uses the same three vertices as " +
                        (faceLines.empty() ? "triangle " + std::to_string(it->second)
                                           : "the face of line " + std::to_string(faceLines[it->second])) +
                        " (a duplicated face)");
        out.faces.push_back(g);
    }
    if (out.faces.empty()) throw Error(file + ": the mesh has no triangles");
    // Positions no face uses (stray vertices, points and lines) would be nodes without mass.
    std::vector<std::uint32_t> compact(out.positions.size(), 0);
    for (const Face& f : out.faces)
        for (std::uint32_t v : f) compact[v] = 1;
    std::vector<glm::dvec3> used;
    for (std::size_t v = 0; v < out.positions.size(); ++v)
        if (compact[v]) {
            compact[v] = static_cast<std::uint32_t>(used.size());
            used.push_back(out.positions[v]);
        }
    for (Face& f : out.faces)
        for (std::uint32_t& v : f) v = compact[v];
    out.positions = std::move(used);
    return out;
}

} // namespace glcollide::detail
