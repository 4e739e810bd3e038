// The on-device self-check of robust precision (src/engine/robust_self_check.hpp) on this device:
// it passes, on both kernel sets (the collision pipeline's, which engines run, and the query's;
// tests/mutants/robust-self-check-*.patch break a kernel the way a driver might and must fail here); a
// disagreement (injected by inverting expected answers through the test hook, while every case still runs on
// the device) is an Error naming the device, the driver, the first wrong case and the count, or a warning in
// warn mode; a pass is remembered by the marker file across processes and by the process itself without a
// cache; an Engine with robust collisions runs it.
//
// Every test starts from a fresh cache folder and forgets the process's remembered passes, so
// each one decides for itself whether the check runs.

#include "engine/robust_self_check.hpp"
#include "scoped_cache_dir.hpp"
#include "support/two_tet_boxes_scene.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/gl_info.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace glcollide {
namespace {

using engine::runRobustSelfCheck;
using test::FreshCacheDir;
using test::ScopedEnv;

class RobustSelfCheckGl : public ::testing::Test {
  protected:
    void SetUp() override { engine::forgetRememberedSelfChecks(); }
    void TearDown() override { engine::forgetRememberedSelfChecks(); }
    FreshCacheDir dir;
};

// The marker files in the folder (it also holds the program cache's entries).
std::size_t markerFiles(const FreshCacheDir& dir) {
    std::size_t n = 0;
    for (const auto& f : dir.files()) n += f.filename().string().rfind("robust-self-check-", 0) == 0 ? 1 : 0;
    return n;
}

std::size_t caseIndex(const std::string& namePrefix) {
    const auto& cases = engine::builtinSelfCheckCases();
    for (std::size_t i = 0; i < cases.size(); ++i)
        if (cases[i].name.rfind(namePrefix, 0) == 0) return i;
    ADD_FAILURE() << "no case " << namePrefix;
    return 0;
}

TEST_F(RobustSelfCheckGl, PassesOnThisDevice) {
    const SelfCheckReport r = runRobustSelfCheck(SelfCheckMode::Error);
    EXPECT_TRUE(r.needed);
    EXPECT_TRUE(r.passed);
    EXPECT_FALSE(r.remembered);
    EXPECT_EQ(r.cases, engine::builtinSelfCheckCases().size());
    EXPECT_GE(r.cases, 300u);
    EXPECT_EQ(r.wrong, 0u);
    EXPECT_EQ(r.message, "");
    EXPECT_GT(r.milliseconds, 0.0);
    ASSERT_FALSE(r.marker.empty());
    EXPECT_EQ(std::filesystem::path(r.marker).parent_path(), dir.path());
    EXPECT_TRUE(std::filesystem::exists(r.marker));
}

// The pass is remembered for the programs that ran: both kernel sets, the collision pipeline's
// (which engines run) and the query's, so a change to either is checked again.
TEST_F(RobustSelfCheckGl, TheMarkerNamesTheKernelsEnginesRun) {
    const SelfCheckReport r = runRobustSelfCheck(SelfCheckMode::Error);
    ASSERT_TRUE(r.passed);
    std::ifstream in(r.marker, std::ios::binary);
    const std::string key((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* program :
         {"tri_tri_filtered", "tri_tri_exact", "tri_tri_query_filtered", "tri_tri_query_exact"})
        EXPECT_NE(key.find(std::string("program: ") + program + " source "), std::string::npos)
            << program << "\n"
            << key;
}

TEST_F(RobustSelfCheckGl, TheMarkerMakesTheNextProcessSkipTheRun) {
    const SelfCheckReport first = runRobustSelfCheck(SelfCheckMode::Error);
    ASSERT_TRUE(first.passed);
    engine::forgetRememberedSelfChecks(); // as a new process would start
    const SelfCheckReport second = runRobustSelfCheck(SelfCheckMode::Error);
    EXPECT_TRUE(second.passed);
    EXPECT_TRUE(second.remembered);
    EXPECT_EQ(second.cases, 0u) << "nothing ran";
    EXPECT_EQ(second.marker, first.marker);
}

TEST_F(RobustSelfCheckGl, AMarkerWithAnotherKeyDoesNotCount) {
    const SelfCheckReport first = runRobustSelfCheck(SelfCheckMode::Error);
    ASSERT_TRUE(first.passed);
    std::ofstream(first.marker, std::ios::trunc) << "glcollide robust self-check 1\nsome other device\n";
    engine::forgetRememberedSelfChecks();
    const SelfCheckReport second = runRobustSelfCheck(SelfCheckMode::Error);
    EXPECT_FALSE(second.remembered);
    EXPECT_EQ(second.cases, first.cases) << "ran again";
    EXPECT_TRUE(second.passed);
}

TEST_F(RobustSelfCheckGl, WithoutACacheTheProcessRemembersThePass) {
    const ScopedEnv off("GLCOLLIDE_CACHE_DIR", "off");
    const SelfCheckReport first = runRobustSelfCheck(SelfCheckMode::Error);
    EXPECT_TRUE(first.passed);
    EXPECT_FALSE(first.remembered);
    EXPECT_EQ(first.marker, "");
    const SelfCheckReport second = runRobustSelfCheck(SelfCheckMode::Error);
    EXPECT_TRUE(second.remembered);
    EXPECT_EQ(second.cases, 0u);
    EXPECT_TRUE(dir.files().empty());
}

TEST_F(RobustSelfCheckGl, ADisagreementIsAnErrorNamingDeviceDriverAndCase) {
    const std::size_t hypotenuse = caseIndex("coplanar, one float step off the hypotenuse");
    const std::size_t denormal = caseIndex("denormal triangle pierced");
    const engine::SelfCheckInjection injection{{denormal, hypotenuse}};
    const GlInfo gl = queryGlInfo();
    const auto& c = engine::builtinSelfCheckCases()[std::min(hypotenuse, denormal)];
    const bool truth = cpu::exactPairIntersects(c.pair);
    try {
        (void)runRobustSelfCheck(SelfCheckMode::Error, injection);
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("device \"" + gl.renderer + "\""), std::string::npos) << m;
        EXPECT_NE(m.find("driver \"" + gl.vendor + " " + gl.version + "\""), std::string::npos) << m;
        EXPECT_NE(m.find("2 of " + std::to_string(engine::builtinSelfCheckCases().size())), std::string::npos)
            << m;
        EXPECT_NE(m.find("\"" + c.name + "\": " + engine::formatTriPair(c.pair)), std::string::npos) << m;
        // The device answered the truth; the injected expectation is its inverse.
        EXPECT_NE(m.find(std::string("expected ") + (truth ? "0" : "1") + " "), std::string::npos) << m;
        EXPECT_NE(m.find(std::string("got ") + (truth ? "1" : "0") + " "), std::string::npos) << m;
    }
    EXPECT_EQ(markerFiles(dir), 0u) << "a failure leaves no marker";
}

TEST_F(RobustSelfCheckGl, WarnModeReturnsTheDisagreementAndRemembersNothing) {
    const engine::SelfCheckInjection injection{{caseIndex("far away, crossing")}};
    for (int i = 0; i < 2; ++i) {
        const SelfCheckReport r = runRobustSelfCheck(SelfCheckMode::Warn, injection);
        EXPECT_FALSE(r.passed);
        EXPECT_FALSE(r.remembered) << "a failure is checked again every time";
        EXPECT_EQ(r.wrong, 1u);
        EXPECT_NE(r.firstWrong.find("far away, crossing"), std::string::npos) << r.firstWrong;
        EXPECT_NE(r.message.find("self-check failed on device"), std::string::npos) << r.message;
        EXPECT_EQ(r.marker, "");
    }
    EXPECT_EQ(markerFiles(dir), 0u);
}

TEST_F(RobustSelfCheckGl, OffRunsNothing) {
    const SelfCheckReport r = runRobustSelfCheck(SelfCheckMode::Off);
    EXPECT_FALSE(r.needed);
    EXPECT_EQ(r.cases, 0u);
    EXPECT_EQ(markerFiles(dir), 0u);
}

TEST_F(RobustSelfCheckGl, TheEnvironmentVariableWins) {
    {
        const ScopedEnv env("GLCOLLIDE_SELF_CHECK", "off");
        EXPECT_EQ(engine::effectiveSelfCheckMode(SelfCheckMode::Error), SelfCheckMode::Off);
    }
    {
        const ScopedEnv env("GLCOLLIDE_SELF_CHECK", "warn");
        EXPECT_EQ(engine::effectiveSelfCheckMode(SelfCheckMode::Error), SelfCheckMode::Warn);
    }
    {
        const ScopedEnv env("GLCOLLIDE_SELF_CHECK", "error");
        EXPECT_EQ(engine::effectiveSelfCheckMode(SelfCheckMode::Off), SelfCheckMode::Error);
    }
    EXPECT_EQ(engine::effectiveSelfCheckMode(SelfCheckMode::Warn), SelfCheckMode::Warn)
        << "unset: the option";
    const ScopedEnv env("GLCOLLIDE_SELF_CHECK", "sometimes");
    EXPECT_THROW((void)engine::effectiveSelfCheckMode(SelfCheckMode::Error), Error);
}

TEST_F(RobustSelfCheckGl, AnEngineWithRobustCollisionsRunsItOnce) {
    const Engine first(test::twoOverlappingTetBoxes("robust"));
    const SelfCheckReport& r = first.setupStats().robustSelfCheck;
    EXPECT_TRUE(r.needed);
    EXPECT_TRUE(r.passed);
    EXPECT_EQ(r.cases, engine::builtinSelfCheckCases().size());
    bool queryProgram = false;
    for (const ProgramSetup& p : first.setupStats().programs)
        queryProgram |= p.shader == "tri_tri_query_filtered";
    EXPECT_TRUE(queryProgram) << "the check's programs count as setup";
    const Engine second(test::twoOverlappingTetBoxes("robust"));
    EXPECT_TRUE(second.setupStats().robustSelfCheck.remembered);
    EXPECT_TRUE(second.warnings().empty());
}

TEST_F(RobustSelfCheckGl, FastPrecisionOrOffNeedsNoCheck) {
    const Engine fast(test::twoOverlappingTetBoxes("fast"));
    EXPECT_FALSE(fast.setupStats().robustSelfCheck.needed);
    EngineOptions options;
    options.robustSelfCheck = SelfCheckMode::Off;
    const Engine off(test::twoOverlappingTetBoxes("robust"), options);
    EXPECT_FALSE(off.setupStats().robustSelfCheck.needed);
    EXPECT_EQ(off.setupStats().robustSelfCheck.mode, SelfCheckMode::Off);
    EXPECT_EQ(markerFiles(dir), 0u);
}

} // namespace
} // namespace glcollide
