// TetGen .node/.ele reader on hand-made files.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

using namespace glcollide;
using namespace glcollide::detail;
using ::testing::HasSubstr;

namespace {

const std::string kData = GLCOLLIDE_TEST_DATA_DIR "/mesh/";

std::string errorOf(const std::string& file) {
    try {
        readTetGen(kData + file);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(TetGenReader, ZeroAndOneBasedGiveTheSameMesh) {
    const TetMesh zero = readTetGen(kData + "two_tets0.node");
    const TetMesh one = readTetGen(kData + "two_tets1.node");
    ASSERT_EQ(zero.positions.size(), 5u);
    ASSERT_EQ(zero.tets.size(), 2u);
    EXPECT_EQ(zero.positions, one.positions);
    EXPECT_EQ(zero.positions[4], glm::dvec3(1, 1, 1));
    // two_tets0.ele writes its second tet inverted (1 3 2 4); orientation swaps its last two nodes.
    EXPECT_EQ(zero.tets, (std::vector<Tet>{{0, 1, 2, 3}, {1, 3, 4, 2}}));
    EXPECT_EQ(one.tets, (std::vector<Tet>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
    EXPECT_EQ(zero.tetLines, (std::vector<std::size_t>{3, 4}));
    for (const Tet& t : zero.tets)
        EXPECT_GT(
            tetDet(zero.positions[t[0]], zero.positions[t[1]], zero.positions[t[2]], zero.positions[t[3]]),
            0.0);
    EXPECT_EQ(boundaryFaces(zero.tets, "two tets").size(), 6u);
}

TEST(TetGenReader, ErrorsNameFileAndLine) {
    EXPECT_THAT(errorOf("tet10.node"), HasSubstr("tet10.ele:1: 10-node"));
    EXPECT_THAT(errorOf("bad_index.node"), HasSubstr("bad_index.ele:3: node index 9 out of range [1, 5]"));
    EXPECT_THAT(errorOf("missing_ele.node"), HasSubstr("missing_ele.ele: cannot open file"));
    EXPECT_THAT(errorOf("nope.node"), HasSubstr("nope.node: cannot open file"));
}
