// AABB-octree layout (src/model/octree_layout.cpp): cell mapping, face->box assignment and CSR
// order. Feature ownership and closed flags: features_test.cpp; the collision twin's building
// blocks: collision_twin_test.cpp.

#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include "model_of.hpp"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <set>

namespace glcollide {
namespace {

using test::modelOf;

TEST(Octree, CellsClampAndFlatAxes) {
    const glm::dvec3 lo(0.0), hi(1.0, 2.0, 4.0);
    EXPECT_EQ(model::octreeCell({0.0, 0.0, 0.0}, lo, hi, 2), 0u);
    EXPECT_EQ(model::octreeCell({1.0, 2.0, 4.0}, lo, hi, 2), 7u);  // the upper border is clamped in
    EXPECT_EQ(model::octreeCell({0.75, 0.1, 0.1}, lo, hi, 2), 1u); // x fastest
    EXPECT_EQ(model::octreeCell({0.1, 1.5, 0.1}, lo, hi, 2), 2u);
    EXPECT_EQ(model::octreeCell({0.1, 0.1, 3.0}, lo, hi, 2), 4u);
    EXPECT_EQ(model::octreeCell({-5.0, 9.0, 0.5}, lo, hi, 4), 0u + 4u * 3u + 16u * 0u);
    // A flat axis maps to cell 0 on that axis.
    EXPECT_EQ(model::octreeCell({0.9, 7.0, 0.9}, glm::dvec3(0.0, 7.0, 0.0), glm::dvec3(1.0, 7.0, 1.0), 2),
              1u + 4u);
}

TEST(Octree, DepthOutOfRangeThrows) {
    const model::FlatModel m = modelOf({detail::generateTetBox({1, 1, 1}, {1, 1, 1})});
    EXPECT_THROW(model::buildOctree(m, 0), Error);
    EXPECT_THROW(model::buildOctree(m, 4), Error);
}

TEST(Octree, FacesGoToTheCellOfTheirRestCentroid) {
    const model::FlatModel m =
        modelOf({detail::generateTetBox({1, 2, 3}, {3, 4, 5}), detail::generateSphere(0.5, 2)});
    for (int depth = 1; depth <= 3; ++depth) {
        const model::OctreeLayout o = model::buildOctree(m, depth);
        const std::uint32_t n = 1u << depth;
        EXPECT_EQ(o.cellsPerAxis, n);
        EXPECT_EQ(o.boxesPerObject, n * n * n);
        EXPECT_EQ(o.boxCount, 2 * n * n * n);
        ASSERT_EQ(o.boxFaces.offsets.size(), o.boxCount + 1u);
        ASSERT_EQ(o.boxFaces.items.size(), m.faceCount());
        std::set<std::uint32_t> cellsUsed;
        for (std::size_t obj = 0; obj < m.objects.size(); ++obj) {
            const model::ObjectRange& r = m.objects[obj];
            EXPECT_EQ(o.firstBox[obj], obj * o.boxesPerObject);
            glm::dvec3 lo(1e300), hi(-1e300);
            for (std::uint32_t k = 3 * r.firstFace; k < 3 * (r.firstFace + r.faceCount); ++k) {
                lo = glm::min(lo, m.positions[m.faceIndices[k]]);
                hi = glm::max(hi, m.positions[m.faceIndices[k]]);
            }
            for (std::uint32_t f = r.firstFace; f < r.firstFace + r.faceCount; ++f) {
                const glm::dvec3 c =
                    (m.positions[m.faceIndices[3 * f]] + m.positions[m.faceIndices[3 * f + 1]] +
                     m.positions[m.faceIndices[3 * f + 2]]) /
                    3.0;
                EXPECT_EQ(o.faceObject[f], obj);
                EXPECT_EQ(o.faceBox[f], o.firstBox[obj] + model::octreeCell(c, lo, hi, n));
                cellsUsed.insert(o.faceBox[f]);
            }
        }
        EXPECT_GT(cellsUsed.size(), std::size_t{8}); // the faces spread over many cells
        // CSR rows: exactly the faces assigned to the box, in increasing face index.
        for (std::uint32_t b = 0; b < o.boxCount; ++b) {
            const auto first = o.boxFaces.items.begin() + o.boxFaces.offsets[b];
            const auto last = o.boxFaces.items.begin() + o.boxFaces.offsets[b + 1];
            EXPECT_TRUE(std::is_sorted(first, last));
            for (auto it = first; it != last; ++it) EXPECT_EQ(o.faceBox[*it], b);
        }
    }
}
} // namespace
} // namespace glcollide
