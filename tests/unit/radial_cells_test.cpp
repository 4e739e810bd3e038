// Radial view-based culling's footprint cells (shaders/common/radial_cells.glsl, compiled as C++ by
// cpu/radial_library.hpp): RadialFree skips its scan of a face whose cells no listed face marked,
// which leaves every answer unchanged only if two footprints that the meeting tests call meeting
// (glcRadialFootprintsMeet, glcRadialFeetMeet, as computed in float with their slack) always share a
// (cell, bin). Checked here on random cones whose axes lie near the meeting limit (where the slack
// decides), on cones of real footprints, and on feet with ends at bin boundaries, NaN (not in the
// relaxed-float build, whose compiler may assume there is none) and inverted;
// also that the cells hold every direction of a cone (double precision) and that a small cone covers
// few cells (else the cells would skip nothing), and that the two grids' words are disjoint. Also in the
// relaxed-float build (fast-math, FMA, FTZ/DAZ).

#include "cpu/radial_library.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace glcollide {
namespace {

constexpr int kGrid = GLC_RADIAL_CELL_GRID, kCoarse = GLC_RADIAL_COARSE_GRID;

bool boxesShareACell(const glm::vec4& a, const glm::vec4& b, int grid) {
    const glm::ivec3 loA = shader::glcRadialCellsLow(a, grid), hiA = shader::glcRadialCellsHigh(a, grid);
    const glm::ivec3 loB = shader::glcRadialCellsLow(b, grid), hiB = shader::glcRadialCellsHigh(b, grid);
    for (int k = 0; k < 3; ++k)
        if (std::max(loA[k], loB[k]) > std::min(hiA[k], hiB[k])) return false;
    return true;
}

/// Both grids: RadialClassify marks a listed footprint in one of them, RadialFree looks at both.
bool boxesShareACell(const glm::vec4& a, const glm::vec4& b) {
    return boxesShareACell(a, b, kGrid) && boxesShareACell(a, b, kCoarse);
}

/// The statement the proof makes before cells: each coordinate of the axes is within the two reaches.
bool reachesOverlap(const glm::vec4& a, const glm::vec4& b) {
    const double r = double{shader::glcRadialCellReach(a)} + double{shader::glcRadialCellReach(b)};
    for (int k = 0; k < 3; ++k)
        if (std::abs(double{a[k]} - double{b[k]}) > r) return false;
    return true;
}

/// A float unit vector as the shaders make one (normalize in float).
glm::vec3 randomAxis(std::mt19937& rng) {
    std::normal_distribution<float> n(0.0f, 1.0f);
    for (;;) {
        const glm::vec3 v(n(rng), n(rng), n(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

/// `a` turned by `angle` towards a direction perpendicular to it (in double, rounded to float).
glm::vec3 turned(const glm::vec3& a, const glm::vec3& towards, double angle) {
    const glm::dvec3 ad(a), t = glm::normalize(glm::dvec3(towards) - glm::dot(glm::dvec3(towards), ad) * ad);
    return glm::vec3(std::cos(angle) * ad + std::sin(angle) * t);
}

TEST(RadialCells, ConesThatTheMeetingTestCallsMeetingShareACell) {
    std::mt19937 rng(24);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int meetingBeyondTheirAngles = 0, meeting = 0, apart = 0;
    for (int i = 0; i < 400000; ++i) {
        // Half-angles from 0.0005 to 1.5 rad (log-uniform); some cones are every direction.
        const double ta = 0.0005 * std::pow(3000.0, u(rng)), tb = 0.0005 * std::pow(3000.0, u(rng));
        glm::vec3 a = randomAxis(rng), towards = randomAxis(rng);
        if (i % 4 ==
            0) { // a along a coordinate axis, turned in a coordinate plane: a - b nearly along an axis
            a = glm::vec3(0.0f);
            a[i / 4 % 3] = (i / 12) % 2 ? 1.0f : -1.0f;
            towards = glm::vec3(0.0f);
            towards[(i / 4 + 1) % 3] = 1.0f;
        }
        // The axes' angle near the limit ta + tb, where only the slack decides.
        const double angle = std::max(0.0, ta + tb + (u(rng) - 0.5) * 0.04);
        const glm::vec3 b = turned(a, towards, angle);
        glm::vec4 coneA(a, static_cast<float>(std::cos(ta)) - 6.103515625e-5f);
        glm::vec4 coneB(b, static_cast<float>(std::cos(tb)) - 6.103515625e-5f);
        if (i % 97 == 0) coneA = shader::glcRadialEverywhere();
        if (!shader::glcRadialFootprintsMeet(coneA, coneB)) {
            ++apart;
            continue;
        }
        ++meeting;
        if (angle > ta + tb) ++meetingBeyondTheirAngles;
        ASSERT_TRUE(reachesOverlap(coneA, coneB))
            << "pair " << i << ": angles " << ta << " + " << tb << ", axes " << angle;
        ASSERT_TRUE(boxesShareACell(coneA, coneB)) << "pair " << i;
    }
    // Not vacuous: many pairs meet only by the slack, and many do not meet at all.
    EXPECT_GT(meetingBeyondTheirAngles, 10000);
    EXPECT_GT(meeting, 100000);
    EXPECT_GT(apart, 100000);
}

TEST(RadialCells, FootprintsOfRandomTrianglesThatMeetShareACell) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto v = [&](float r) { return glm::vec3(u(rng), u(rng), u(rng)) * r; };
    const auto footprint = [&](const glm::vec3& q) {
        const glm::vec3 centre = q + 0.3f * randomAxis(rng);
        const glm::vec3 p0 = centre + v(0.05f), p1 = centre + v(0.05f), p2 = centre + v(0.05f);
        const glm::vec3 m = v(0.02f);
        return shader::glcRadialFootprint(p0, p1, p2, q, p0 + m + v(0.01f), p1 + m + v(0.01f),
                                          p2 + m + v(0.01f), q + v(0.01f));
    };
    int meeting = 0;
    for (int i = 0; i < 200000; ++i) {
        const glm::vec3 q = v(2.0f);
        const glm::vec4 a = footprint(q), b = footprint(q);
        if (!shader::glcRadialFootprintsMeet(a, b)) continue;
        ++meeting;
        ASSERT_TRUE(reachesOverlap(a, b)) << "pair " << i;
        ASSERT_TRUE(boxesShareACell(a, b)) << "pair " << i;
    }
    EXPECT_GT(meeting, 1000);
}

TEST(RadialCells, EveryDirectionOfAConeLiesInItsCells) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 20000; ++i) {
        const double theta = 0.001 * std::pow(1500.0, u(rng));
        const glm::vec3 a = randomAxis(rng);
        const glm::vec4 cone(a, static_cast<float>(std::cos(theta)));
        for (const int grid : {kGrid, kCoarse}) {
            const glm::ivec3 lo = shader::glcRadialCellsLow(cone, grid),
                             hi = shader::glcRadialCellsHigh(cone, grid);
            for (int k = 0; k < 20; ++k) { // directions at the cone's rim and inside it, in double
                const glm::dvec3 d =
                    glm::normalize(glm::dvec3(turned(a, randomAxis(rng), theta * (k < 10 ? 1.0 : u(rng)))));
                for (int c = 0; c < 3; ++c) {
                    const int cell =
                        std::min(static_cast<int>(std::floor((d[c] + 1.0) * 0.5 * grid)), grid - 1);
                    ASSERT_LE(lo[c], cell) << "cone " << i;
                    ASSERT_GE(hi[c], cell) << "cone " << i;
                }
            }
        }
    }
}

TEST(RadialCells, FeetThatTheMeetingTestCallsMeetingShareABin) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
#ifdef GLCOLLIDE_RELAXED_FLOAT
    // -ffinite-math-only lets the compiler drop the NaN checks, and NaN then reaches a float-to-int
    // conversion (undefined in C++; UBSan stops there): NaN feet are outside that build's contract.
    constexpr bool kNaNs = false;
#else
    constexpr bool kNaNs = true;
#endif
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const auto end = [&](int kind) {
        switch (kind % 6) {
        case 0:
            return static_cast<float>(static_cast<int>(u(rng) * 9.0f)) / 8.0f; // a bin boundary, 0 or 1
        case 1:
            return std::nextafter(static_cast<float>(static_cast<int>(u(rng) * 9.0f)) / 8.0f, 0.0f);
        case 2:
            return std::nextafter(static_cast<float>(static_cast<int>(u(rng) * 9.0f)) / 8.0f, 1.0f);
        case 3:
            return kind == 3 && kNaNs ? nan : u(rng);
        default:
            return u(rng);
        }
    };
    int meeting = 0;
    for (int i = 0; i < 400000; ++i) {
        glm::vec2 a(end(static_cast<int>(u(rng) * 6.0f)), end(static_cast<int>(u(rng) * 6.0f)));
        glm::vec2 b(end(static_cast<int>(u(rng) * 6.0f)), end(static_cast<int>(u(rng) * 6.0f)));
        if (i % 3 !=
            0) { // mostly ordered intervals; some inverted ones, which the test may still call meeting
            if (a.x > a.y) std::swap(a.x, a.y);
            if (b.x > b.y) std::swap(b.x, b.y);
        }
        if (!shader::glcRadialFeetMeet(a, b)) continue;
        ++meeting;
        ASSERT_NE(shader::glcRadialFootBins(a) & shader::glcRadialFootBins(b), 0u)
            << "[" << a.x << ", " << a.y << "] and [" << b.x << ", " << b.y << "]";
    }
    EXPECT_GT(meeting, 100000);
    EXPECT_EQ(shader::glcRadialFootBins(shader::glcRadialWholeSegment()), 0xffu);
    EXPECT_EQ(shader::glcRadialFootBins(glm::vec2(0.25f, 0.25f)), 1u << 2); // a point: its bin only
    EXPECT_EQ(shader::glcRadialFootBins(glm::vec2(0.3f, 0.2f)), 0xffu);     // inverted: every bin
}

TEST(RadialCells, ASmallConeCoversAFewCellsAndEveryDirectionCoversThemAll) {
    std::mt19937 rng(5);
    const auto cells = [](const glm::vec4& cone, int grid) {
        return shader::glcRadialCellCount(shader::glcRadialCellsLow(cone, grid),
                                          shader::glcRadialCellsHigh(cone, grid));
    };
    for (int i = 0; i < 10000; ++i) {
        // A face of the 4,992-face sleeve seen from its axis: about 3 degrees.
        const glm::vec4 cone(randomAxis(rng), static_cast<float>(std::cos(3.0 * M_PI / 180.0)));
        ASSERT_GE(cells(cone, kGrid), 1);
        ASSERT_LE(cells(cone, kGrid), 27); // the box is 0.14 wide, a cell 0.125: at most 3 cells per axis
        ASSERT_LE(cells(cone, kCoarse), 8);
    }
    const glm::vec4 everywhere = shader::glcRadialEverywhere();
    EXPECT_EQ(cells(everywhere, kGrid), kGrid * kGrid * kGrid);
    EXPECT_EQ(cells(everywhere, kCoarse), kCoarse * kCoarse * kCoarse);
    // A footprint too wide for the fine grid is marked in the coarse one: at most 64 cells there too.
    EXPECT_GT(cells(everywhere, kGrid), shader::GLC_RADIAL_MOST_MARKED_CELLS);
    EXPECT_LE(cells(everywhere, kCoarse), shader::GLC_RADIAL_MOST_MARKED_CELLS);
}

/// The words of the two grids of two observers do not overlap, and fill GLC_RADIAL_CELL_WORDS.
TEST(RadialCells, TheGridsOfEachObserverHaveWordsOfTheirOwn) {
    std::vector<int> owner(2 * GLC_RADIAL_CELL_WORDS, 0);
    for (std::uint32_t observer = 0; observer < 2; ++observer)
        for (const int grid : {kGrid, kCoarse})
            for (int z = 0; z < grid; ++z)
                for (int y = 0; y < grid; ++y)
                    for (int x = 0; x < grid; ++x) {
                        const std::uint32_t word = shader::glcRadialCellWord(observer, grid, x, y, z);
                        ASSERT_LT(word, owner.size());
                        const int id = static_cast<int>(observer) * 2 + (grid == kGrid ? 1 : 2);
                        ASSERT_TRUE(owner[word] == 0 || owner[word] == id) << "word " << word;
                        owner[word] = id;
                        ASSERT_LT(shader::glcRadialCellShift(x), 32u);
                    }
    EXPECT_EQ(std::count(owner.begin(), owner.end(), 0), 0); // every word used
}

} // namespace
} // namespace glcollide
