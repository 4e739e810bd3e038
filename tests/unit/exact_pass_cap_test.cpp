// The exact pass's cap on recorded signs (GLC_MAX_EXACT, shaders/common/tri_tri_robust.glsl) is an
// error, never an answer: this translation unit compiles the shader library as C++ with the cap
// lowered to 3, so that ordinary hard cases reach it. A pair that needs more recorded signs must
// set glcExactFailed (robustTrianglesIntersect then throws); every other pair must still get the
// oracle's answer. With the real cap (128) no pair reaches it: a run asks at most 120 predicates
// (tests/unit/shader_library_test.cpp measures it).

#define GLC_MAX_EXACT 3
#include "cpu/oracle/tri_tri_cases.hpp"
#include "cpu/shader_library.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace glcollide {
namespace {

using glm::vec3;
namespace sh = shader;

TEST(ExactPassCap, ReachingTheCapIsAnErrorNotAnAnswer) {
    static_assert(GLC_MAX_EXACT == 3, "this test needs the lowered cap");
    int failed = 0, answered = 0;
    for (const cpu::NamedTriPair& c : cpu::hardTriTriCases()) {
        auto v = [&](int k) {
            const auto i = static_cast<std::size_t>(3 * k);
            return vec3(c.pair[i], c.pair[i + 1], c.pair[i + 2]);
        };
        const bool hit = sh::glcTriTriExact(v(0), v(1), v(2), v(3), v(4), v(5));
        if (sh::glcExactFailed) {
            ++failed;
            EXPECT_EQ(sh::glcExactKnown, GLC_MAX_EXACT) << c.name << ": failed before the cap";
            // The composed answer (the filtered pass first) throws whenever it needs the exact pass.
            if (sh::glcTriTriFiltered(v(0), v(1), v(2), v(3), v(4), v(5)) == sh::GLC_UNDECIDED) {
                EXPECT_THROW((void)sh::robustTrianglesIntersect(v(0), v(1), v(2), v(3), v(4), v(5)), Error)
                    << c.name;
            }
            continue;
        }
        ++answered;
        EXPECT_EQ(hit, cpu::exactPairIntersects(c.pair)) << c.name;
    }
    EXPECT_GT(failed, 10) << "the lowered cap must be reached, or this tests nothing";
    EXPECT_GT(answered, 100);
}

TEST(ExactPassCap, TheErrorNamesTheCap) {
    for (const cpu::NamedTriPair& c : cpu::hardTriTriCases()) {
        auto v = [&](int k) {
            const auto i = static_cast<std::size_t>(3 * k);
            return vec3(c.pair[i], c.pair[i + 1], c.pair[i + 2]);
        };
        (void)sh::glcTriTriExact(v(0), v(1), v(2), v(3), v(4), v(5));
        if (!sh::glcExactFailed ||
            sh::glcTriTriFiltered(v(0), v(1), v(2), v(3), v(4), v(5)) != sh::GLC_UNDECIDED)
            continue;
        try {
            (void)sh::robustTrianglesIntersect(v(0), v(1), v(2), v(3), v(4), v(5));
            FAIL() << "no error";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("more than 3 recorded signs"), std::string::npos)
                << e.what();
        }
        return;
    }
    FAIL() << "no hard case reaches the lowered cap";
}

} // namespace
} // namespace glcollide
