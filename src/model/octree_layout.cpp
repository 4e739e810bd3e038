#include "model/octree_layout.hpp"

#include "model/features.hpp"

#include <glcollide/error.hpp>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace glcollide::model {
namespace {

std::uint32_t axisCell(double x, double lo, double hi, std::uint32_t n) {
    if (!(hi > lo)) return 0;
    const double t = std::floor((x - lo) / (hi - lo) * static_cast<double>(n));
    if (!(t >= 0.0)) return 0; // also NaN
    return std::min(static_cast<std::uint32_t>(std::min(t, static_cast<double>(n - 1))), n - 1);
}

} // namespace

std::uint32_t octreeCell(const glm::dvec3& point, const glm::dvec3& lo, const glm::dvec3& hi,
                         std::uint32_t cellsPerAxis) {
    const std::uint32_t n = cellsPerAxis;
    return axisCell(point.x, lo.x, hi.x, n) +
           n * (axisCell(point.y, lo.y, hi.y, n) + n * axisCell(point.z, lo.z, hi.z, n));
}

OctreeLayout buildOctree(const FlatModel& model, int depth) {
    if (depth < 1 || depth > 3)
        throw Error("octree depth " + std::to_string(depth) + " is out of range 1..3");
    OctreeLayout o;
    o.depth = depth;
    o.cellsPerAxis = 1u << depth;
    o.boxesPerObject = o.cellsPerAxis * o.cellsPerAxis * o.cellsPerAxis;
    o.boxCount = static_cast<std::uint32_t>(model.objects.size()) * o.boxesPerObject;
    const std::size_t faces = model.faceCount();
    o.faceObject.assign(faces, 0u);
    o.faceBox.assign(faces, 0u);
    for (std::size_t obj = 0; obj < model.objects.size(); ++obj) {
        const ObjectRange& r = model.objects[obj];
        const std::uint32_t firstBox = static_cast<std::uint32_t>(obj) * o.boxesPerObject;
        o.firstBox.push_back(firstBox);
        o.closed.push_back(isClosedSurface(model.faceIndices, r.firstFace, r.faceCount) ? 1 : 0);
        // The rest-pose box of the object's face vertices (nodes no face uses do not collide).
        glm::dvec3 lo(INFINITY), hi(-INFINITY);
        for (std::uint32_t f = r.firstFace; f < r.firstFace + r.faceCount; ++f)
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3& p = model.positions[model.faceIndices[3 * f + static_cast<std::size_t>(k)]];
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        for (std::uint32_t f = r.firstFace; f < r.firstFace + r.faceCount; ++f) {
            const glm::dvec3 centroid =
                (model.positions[model.faceIndices[3 * f]] + model.positions[model.faceIndices[3 * f + 1]] +
                 model.positions[model.faceIndices[3 * f + 2]]) /
                3.0;
            o.faceObject[f] = static_cast<std::uint32_t>(obj);
            o.faceBox[f] = firstBox + octreeCell(centroid, lo, hi, o.cellsPerAxis);
        }
    }
    // CSR by counting sort: stable in face index, so each row lists its faces in increasing order.
    o.boxFaces.offsets.assign(static_cast<std::size_t>(o.boxCount) + 1, 0u);
    for (std::uint32_t box : o.faceBox) ++o.boxFaces.offsets[box + 1];
    for (std::size_t b = 0; b < o.boxCount; ++b) o.boxFaces.offsets[b + 1] += o.boxFaces.offsets[b];
    o.boxFaces.items.assign(faces, 0u);
    std::vector<std::uint32_t> cursor(o.boxFaces.offsets.begin(), o.boxFaces.offsets.end() - 1);
    for (std::uint32_t f = 0; f < faces; ++f) o.boxFaces.items[cursor[o.faceBox[f]]++] = f;
    o.faceOwned = ownedFeatures(model.faceIndices);
    return o;
}

} // namespace glcollide::model
