#include "app/mesh_export.hpp"

#include <glcollide/error.hpp>

#include <cstdio>
#include <fstream>

namespace glcollide::app {

MeshFormat parseMeshFormat(const std::string& text) {
    if (text == "obj") return MeshFormat::Obj;
    if (text == "ply") return MeshFormat::Ply;
    throw Error("unknown export format '" + text + "' (expected obj or ply)");
}

std::string frameFileName(std::uint64_t frame, MeshFormat format) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%06llu.%s", static_cast<unsigned long long>(frame),
                  format == MeshFormat::Obj ? "obj" : "ply");
    return name;
}

void writeFrameMesh(const std::filesystem::path& path, MeshFormat format, const Scene& scene,
                    const std::vector<std::uint32_t>& bodyFirstNodes,
                    const std::vector<glm::dvec3>& positions) {
    std::ofstream out(path);
    if (!out) throw Error(path.string() + ": cannot open for writing");
    char line[160];
    auto vertex = [&](const glm::dvec3& x, const char* prefix) {
        // %.9g round-trips a float: the GPU state loses nothing in the file.
        std::snprintf(line, sizeof line, "%s%.9g %.9g %.9g\n", prefix, x.x, x.y, x.z);
        out << line;
    };
    if (format == MeshFormat::Obj) {
        out << "# glcollide frame: " << scene.name << "\n";
        for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
            const Body& body = scene.bodies[b];
            out << "o " << (body.name.empty() ? "body" + std::to_string(b) : body.name) << "\n";
            for (std::size_t i = 0; i < body.positions.size(); ++i)
                vertex(positions[bodyFirstNodes[b] + i], "v ");
            for (const auto& f : body.faces) {
                const std::uint32_t base = bodyFirstNodes[b] + 1; // OBJ is 1-based and global
                out << "f " << base + f[0] << ' ' << base + f[1] << ' ' << base + f[2] << "\n";
            }
        }
    } else {
        std::size_t faces = 0;
        for (const Body& body : scene.bodies) faces += body.faces.size();
        out << "ply\nformat ascii 1.0\ncomment glcollide frame: " << scene.name << "\n"
            << "element vertex " << positions.size() << "\nproperty float x\nproperty float y\n"
            << "property float z\nelement face " << faces << "\nproperty list uchar uint vertex_indices\n"
            << "end_header\n";
        for (const glm::dvec3& x : positions) vertex(x, "");
        for (std::size_t b = 0; b < scene.bodies.size(); ++b)
            for (const auto& f : scene.bodies[b].faces)
                out << "3 " << bodyFirstNodes[b] + f[0] << ' ' << bodyFirstNodes[b] + f[1] << ' '
                    << bodyFirstNodes[b] + f[2] << "\n";
    }
    if (!out) throw Error(path.string() + ": write failed");
}

} // namespace glcollide::app
