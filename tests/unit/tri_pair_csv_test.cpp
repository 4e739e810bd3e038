// The triangle-pair CSV reader of `glcollide query tritri` (src/scene/tri_pair_csv.cpp): what it
// accepts (spaces, blank and comment lines, float rounding) and that every bad row is an Error
// naming the file, the line and what is wrong.

#include "scene/tri_pair_csv.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace glcollide {
namespace {

const std::string kRow = "0,0,0, 1,0,0, 0,1,0, 0.25,0.25,-1, 0.25,0.25,1, 1,1,1";

std::string errorOf(const std::string& text) {
    try {
        parseTriPairCsv(text, "pairs.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(TriPairCsv, ParsesRowsSkippingBlankAndCommentLines) {
    const TriPairCsv csv = parseTriPairCsv(
        "# header comment\n\n" + kRow + "\r\n   \n  # indented comment\n\t" + kRow + "\t", "x.csv");
    ASSERT_EQ(csv.pairs.size(), 2u);
    EXPECT_EQ(csv.lines, (std::vector<std::size_t>{3, 6}));
    EXPECT_EQ(csv.pairs[0][9], 0.25f);
    EXPECT_EQ(csv.pairs[1][11], -1.0f);
    EXPECT_EQ(csv.pairs[1][17], 1.0f);
}

TEST(TriPairCsv, RoundsToFloat) {
    std::string row = "0.1,+2,-3e-3, 1e-45,1e-50,3.4028235e38";
    for (int i = 0; i < 12; ++i) row += ",0";
    const TriPairCsv csv = parseTriPairCsv(row, "x.csv");
    ASSERT_EQ(csv.pairs.size(), 1u);
    EXPECT_EQ(csv.pairs[0][0], 0.1f);
    EXPECT_EQ(csv.pairs[0][1], 2.0f);
    EXPECT_EQ(csv.pairs[0][2], -3e-3f);
    EXPECT_EQ(csv.pairs[0][3], 1e-45f); // the smallest denormal float
    EXPECT_EQ(csv.pairs[0][4], 0.0f);   // below every float: rounds to zero
    EXPECT_EQ(csv.pairs[0][5], 3.4028235e38f);
}

TEST(TriPairCsv, BadRowsNameFileLineAndProblem) {
    using ::testing::HasSubstr;
    EXPECT_THAT(errorOf(kRow + "\n1,2,3\n"), HasSubstr("pairs.csv:2: expected 18 numbers"));
    EXPECT_THAT(errorOf(kRow + "\n1,2,3\n"), HasSubstr("got 3 fields"));
    EXPECT_THAT(errorOf("#c\n" + kRow + ",7\n"), HasSubstr("pairs.csv:2: expected 18 numbers"));
    EXPECT_THAT(errorOf("\n\n" + std::string("x") + kRow.substr(1)),
                HasSubstr("pairs.csv:3: field 1 'x' is not a number"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,nan"),
                HasSubstr("pairs.csv:1: field 18 'nan' is not finite"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,inf"), HasSubstr("field 18 'inf' is not finite"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,1e39"),
                HasSubstr("field 18 '1e39' is outside float range"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,0,0,0,1,1,1,2,2,-1e999"),
                HasSubstr("field 18 '-1e999' is outside float range"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,,0,0,1,1,1,2,2,3"), HasSubstr("field 10 '' is not a number"));
    EXPECT_THAT(errorOf("0,0,0,1,0,0,0,1,0,1 2,0,0,1,1,1,2,2,3"),
                HasSubstr("field 10 '1 2' is not a number"));
    EXPECT_THAT(errorOf("0;0;0"), HasSubstr("got 1 field"));
}

TEST(TriPairCsv, MissingFileIsAnError) {
    EXPECT_THROW(readTriPairCsv("/nonexistent/pairs.csv"), Error);
}

} // namespace
} // namespace glcollide
