// Which objects radial culling may give an observer (decision 0025, "The premise"): closed,
// consistently oriented and connected surfaces only. Checked on hand-made surfaces whose answer
// is known: a tetrahedron (yes), the same with one face flipped (no: inconsistent), with one face
// removed (no: open), two disjoint tetrahedra (no: two components, which could nest), a cloth
// square (no: open), a face repeated (no: an edge run twice one way), no faces (no).

#include "model/radial_surfaces.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace glcollide::model {
namespace {

// Outward-oriented tetrahedron on nodes base..base+3 (counter-clockwise seen from outside).
std::vector<std::uint32_t> tetrahedron(std::uint32_t base) {
    return {base + 0, base + 2, base + 1, base + 0, base + 1, base + 3,
            base + 1, base + 2, base + 3, base + 0, base + 3, base + 2};
}

bool qualifies(const std::vector<std::uint32_t>& faces) {
    return isClosedOrientedConnected(faces, 0, static_cast<std::uint32_t>(faces.size() / 3));
}

TEST(RadialSurfaces, AClosedOrientedConnectedSurfaceQualifies) {
    EXPECT_TRUE(qualifies(tetrahedron(0)));
}

TEST(RadialSurfaces, AFlippedFaceOrAMissingFaceDoesNot) {
    std::vector<std::uint32_t> flipped = tetrahedron(0);
    std::swap(flipped[1], flipped[2]);
    EXPECT_FALSE(qualifies(flipped));
    std::vector<std::uint32_t> open = tetrahedron(0);
    open.resize(9);
    EXPECT_FALSE(qualifies(open));
}

TEST(RadialSurfaces, TwoComponentsDoNot) {
    std::vector<std::uint32_t> two = tetrahedron(0);
    const std::vector<std::uint32_t> second = tetrahedron(4);
    two.insert(two.end(), second.begin(), second.end());
    EXPECT_FALSE(qualifies(two));
    // Each component alone, addressed by its face range, does.
    EXPECT_TRUE(isClosedOrientedConnected(two, 4, 4));
}

TEST(RadialSurfaces, OpenClothRepeatedFacesAndNoFacesDoNot) {
    EXPECT_FALSE(qualifies({0, 1, 2, 1, 3, 2})); // a square of two triangles
    std::vector<std::uint32_t> repeated = tetrahedron(0);
    repeated.insert(repeated.end(), {0, 2, 1});
    EXPECT_FALSE(qualifies(repeated));
    EXPECT_FALSE(qualifies({}));
}

} // namespace
} // namespace glcollide::model
