#pragma once
// Writes a frame's surface meshes as OBJ or PLY (ASCII), one file per frame, so any viewer opens
// them. Positions come from Engine::readPositions(); faces from the scene's bodies.

#include <glcollide/scene.hpp>

#include <glm/vec3.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace glcollide::app {

enum class MeshFormat { Obj, Ply };

/// Parses "obj" or "ply"; throws Error otherwise.
MeshFormat parseMeshFormat(const std::string& text);

/// Writes all bodies of `scene` with the given global node positions. OBJ keeps one `o` group
/// per body; PLY writes one mesh. Throws Error when the file cannot be written.
void writeFrameMesh(const std::filesystem::path& path, MeshFormat format, const Scene& scene,
                    const std::vector<std::uint32_t>& bodyFirstNodes,
                    const std::vector<glm::dvec3>& positions);

/// "frame_000012.obj" style name for a frame index.
std::string frameFileName(std::uint64_t frame, MeshFormat format);

} // namespace glcollide::app
