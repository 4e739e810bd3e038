#include "engine/robust_self_check.hpp"

#include "gl/program_cache.hpp"
#include "gl/setup_stats_sink.hpp"
#include "passes/collision/narrow_phase_batch.hpp"
#include "passes/tri_tri_query_pass.hpp"

#include <glcollide/error.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <set>
#include <utility>

namespace glcollide::engine {
namespace {

// Passes remembered in this process, by key: a fact about a device, driver and shader, so sharing
// it between engines changes nothing but skipping a repeated check.
std::mutex g_rememberedMutex;
std::set<std::string> g_remembered;

bool rememberedInProcess(const std::string& key) {
    const std::lock_guard<std::mutex> lock(g_rememberedMutex);
    return g_remembered.count(key) != 0;
}
void rememberInProcess(const std::string& key) {
    const std::lock_guard<std::mutex> lock(g_rememberedMutex);
    g_remembered.insert(key);
}

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

std::uint64_t hashCases(const std::vector<SelfCheckCase>& cases) {
    std::string bytes;
    for (const SelfCheckCase& c : cases) {
        bytes += c.name;
        bytes.push_back('\0');
        bytes.append(reinterpret_cast<const char*>(c.pair.data()), sizeof c.pair);
    }
    return gl::fnv1a64(bytes);
}

// What a pass is remembered under: the device and driver, the sources of every program the check
// runs (as built, so a rewritten shader is checked again: both kernel sets and the list
// dispatcher), the case set and any test injection.
std::string rememberKey(const gl::DriverIdentity& driver, const std::vector<ProgramSetup>& programs,
                        const std::vector<SelfCheckCase>& cases, const SelfCheckInjection& injection) {
    std::string key = "glcollide robust self-check 2\nvendor: " + driver.vendor +
                      "\nrenderer: " + driver.renderer + "\nversion: " + driver.version + "\n";
    for (const ProgramSetup& p : programs) {
        key += "program: " + p.shader;
        for (const std::string& d : p.defines) key += " " + d;
        key += " source " + hex64(p.sourceHash) + "\n";
    }
    key += "cases: " + std::to_string(cases.size()) + " " + hex64(hashCases(cases)) + "\n";
    if (!injection.invertExpected.empty()) {
        key += "test injection:";
        for (std::size_t i : injection.invertExpected) key += " " + std::to_string(i);
        key += "\n";
    }
    return key;
}

std::optional<std::filesystem::path> markerPath(const std::string& key) {
    const gl::CacheLocation location = gl::cacheLocationFromEnvironment();
    if (!location.enabled) return std::nullopt;
    return location.folder / ("robust-self-check-" + hex64(gl::fnv1a64(key)) + ".pass");
}

bool markerHolds(const std::filesystem::path& path, const std::string& key) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec || size != key.size()) return false;
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text == key; // the full key, so a colliding file name never counts as a pass
}

// The two sets of robust kernels the check runs: the collision pipeline's, which engines run, and
// the query's (glcollide query tritri, benchmarks).
struct CheckKernels {
    passes::NarrowPhaseBatch collision;
    passes::TriTriQueryPass query;
};

// Whether the sink already holds this program (same shader, defines and source).
bool holds(const SetupStats& sink, const ProgramSetup& program) {
    for (const ProgramSetup& p : sink.programs)
        if (p.shader == program.shader && p.defines == program.defines && p.sourceHash == program.sourceHash)
            return true;
    return false;
}

// Builds both kernel sets with their own sink, to learn the programs' sources, and passes the
// programs on to the caller's sink (an Engine's setup statistics) as setup cost, except those the
// caller built itself: an engine with robust collisions has already built tri_tri_filtered,
// tri_tri_exact and list_dispatch_args, and the check's copies (loads from the program cache the
// engine's builds just filled) are part of the check's own time, not a second entry.
CheckKernels buildKernels(std::vector<ProgramSetup>& programs) {
    SetupStats local;
    std::optional<CheckKernels> kernels;
    {
        const gl::SetupStatsScope scope(&local);
        kernels.emplace(CheckKernels{passes::NarrowPhaseBatch(TriTriPrecision::Robust),
                                     passes::TriTriQueryPass(TriTriPrecision::Robust)});
    }
    SetupStats* outer = gl::activeSetupStats();
    if (outer != nullptr) {
        if (outer->cacheFolder.empty()) outer->cacheFolder = local.cacheFolder;
        if (outer->cacheNote.empty()) outer->cacheNote = local.cacheNote;
    }
    for (const ProgramSetup& p : local.programs)
        if (outer == nullptr || !holds(*outer, p)) gl::recordProgramSetup(p);
    programs = std::move(local.programs);
    return std::move(*kernels);
}

std::string failureMessage(const gl::DriverIdentity& driver, const SelfCheckReport& r) {
    return "robust narrow-phase self-check failed on device \"" + driver.renderer + "\", driver \"" +
           driver.vendor + " " + driver.version + "\": " + std::to_string(r.wrong) + " of " +
           std::to_string(r.cases) +
           " built-in cases answered differently from the exact oracle; first: " + r.firstWrong +
           ". Robust precision is not exact on this device; use precision \"fast\", or set "
           "GLCOLLIDE_SELF_CHECK=warn (EngineOptions::robustSelfCheck) to go on anyway "
           "(docs/narrow-phase.md, \"On-device self-check\")";
}

} // namespace

const std::vector<SelfCheckCase>& builtinSelfCheckCases() {
    static const std::vector<SelfCheckCase> cases = [] {
        std::vector<SelfCheckCase> out;
        for (cpu::NamedTriPair& c : cpu::hardTriTriCases()) out.push_back({std::move(c.name), c.pair});
        for (const cpu::TriTriSet set :
             {cpu::TriTriSet::Ulp, cpu::TriTriSet::Scaled, cpu::TriTriSet::Degenerate}) {
            const std::vector<cpu::FloatTriPair> pairs =
                cpu::randomTriTriPairs(set, kSelfCheckSamplePerFamily, kSelfCheckSeed);
            for (std::size_t i = 0; i < pairs.size(); ++i)
                out.push_back({std::string("random ") + cpu::toString(set) + " #" + std::to_string(i) +
                                   " (seed " + std::to_string(kSelfCheckSeed) + ")",
                               pairs[i]});
        }
        return out;
    }();
    return cases;
}

SelfCheckMode parseSelfCheckMode(std::string_view text, std::string_view what) {
    if (text == "error") return SelfCheckMode::Error;
    if (text == "warn") return SelfCheckMode::Warn;
    if (text == "off") return SelfCheckMode::Off;
    throw Error(std::string(what) + ": expected error, warn or off, got '" + std::string(text) + "'");
}

const char* toString(SelfCheckMode mode) {
    switch (mode) {
    case SelfCheckMode::Error:
        return "error";
    case SelfCheckMode::Warn:
        return "warn";
    case SelfCheckMode::Off:
        return "off";
    }
    return "?";
}

SelfCheckMode effectiveSelfCheckMode(SelfCheckMode option) {
    const char* env = std::getenv("GLCOLLIDE_SELF_CHECK");
    if (env == nullptr || env[0] == '\0') return option;
    return parseSelfCheckMode(env, "GLCOLLIDE_SELF_CHECK");
}

std::string formatTriPair(const cpu::FloatTriPair& pair) {
    static const char* const kCorner[6] = {"a0", "a1", "a2", "b0", "b1", "b2"};
    std::string out;
    char text[160];
    for (int k = 0; k < 6; ++k) {
        const auto at = static_cast<std::size_t>(3 * k);
        std::snprintf(text, sizeof text, "%s%s (%.9g, %.9g, %.9g)", k == 0 ? "" : " ", kCorner[k],
                      static_cast<double>(pair[at]), static_cast<double>(pair[at + 1]),
                      static_cast<double>(pair[at + 2]));
        out += text;
    }
    return out;
}

void forgetRememberedSelfChecks() {
    const std::lock_guard<std::mutex> lock(g_rememberedMutex);
    g_remembered.clear();
}

void judgeSelfCheckAnswers(const std::vector<SelfCheckAnswers>& answers, const SelfCheckInjection& injection,
                           SelfCheckReport& report) {
    const std::vector<SelfCheckCase>& cases = builtinSelfCheckCases();
    std::vector<bool> inverted(cases.size(), false);
    for (std::size_t i : injection.invertExpected) inverted.at(i) = true;
    for (const SelfCheckAnswers& a : answers)
        if (a.intersect.size() != cases.size())
            throw Error("self-check: the " + a.kernels + " answered " + std::to_string(a.intersect.size()) +
                        " of " + std::to_string(cases.size()) + " cases");
    report.cases = static_cast<std::uint32_t>(cases.size());
    report.wrong = 0;
    report.firstWrong.clear();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const bool expected = cpu::exactPairIntersects(cases[i].pair) != inverted[i];
        std::string wrongSets; // the kernel sets that answered !expected
        for (const SelfCheckAnswers& a : answers)
            if ((a.intersect[i] != 0) != expected)
                wrongSets += (wrongSets.empty() ? "" : " and the ") + a.kernels;
        if (wrongSets.empty()) continue;
        if (report.wrong++ == 0)
            report.firstWrong = "case " + std::to_string(i) + " \"" + cases[i].name +
                                "\": " + formatTriPair(cases[i].pair) + ", expected " +
                                (expected ? "1 (intersecting)" : "0 (apart)") + ", got " +
                                (expected ? "0 (apart)" : "1 (intersecting)") + " from the " + wrongSets;
    }
}

SelfCheckReport runRobustSelfCheck(SelfCheckMode mode, const SelfCheckInjection& injection) {
    SelfCheckReport report;
    report.mode = mode;
    if (mode == SelfCheckMode::Off) return report;
    report.needed = true;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    };

    const std::vector<SelfCheckCase>& cases = builtinSelfCheckCases();
    for (std::size_t i : injection.invertExpected)
        if (i >= cases.size())
            throw Error("self-check injection: case " + std::to_string(i) + " of " +
                        std::to_string(cases.size()));
    std::vector<ProgramSetup> programs;
    CheckKernels kernels = buildKernels(programs);
    const gl::DriverIdentity driver = gl::currentDriverIdentity();
    const std::string key = rememberKey(driver, programs, cases, injection);
    const std::optional<std::filesystem::path> marker = markerPath(key);
    if (marker) report.marker = marker->string();
    if (rememberedInProcess(key) || (marker && markerHolds(*marker, key))) {
        rememberInProcess(key);
        report.remembered = true;
        report.passed = true;
        report.milliseconds = elapsed();
        return report;
    }

    std::vector<passes::TriTriPair> pairs;
    pairs.reserve(cases.size());
    for (const SelfCheckCase& c : cases) pairs.push_back(c.pair);
    std::vector<SelfCheckAnswers> answers;
    std::string unfinished; // a kernel set that could not answer (its exact pass failed)
    auto answer = [&](const char* name, auto&& run) {
        try {
            answers.push_back({name, run(pairs).intersect});
        } catch (const Error& e) {
            if (unfinished.empty()) unfinished = std::string("the ") + name + " gave no answer: " + e.what();
        }
    };
    answer("collision kernels (tri_tri_filtered, tri_tri_exact)",
           [&](const auto& p) { return kernels.collision.run(p); });
    answer("query kernels (tri_tri_query_filtered, tri_tri_query_exact)",
           [&](const auto& p) { return kernels.query.run(p); });
    judgeSelfCheckAnswers(answers, injection, report);
    if (!unfinished.empty()) {
        report.wrong = report.cases;
        report.firstWrong = unfinished;
    }
    report.passed = report.wrong == 0;
    report.milliseconds = elapsed();
    if (report.passed) {
        rememberInProcess(key);
        if (marker) {
            std::error_code ec;
            std::filesystem::create_directories(marker->parent_path(), ec);
            // Not written (read-only folder, ...): the check runs again next time, nothing worse.
            if (ec || !gl::writeFileAtomically(*marker, key)) report.marker.clear();
        }
        return report;
    }
    report.marker.clear();
    report.message = failureMessage(driver, report);
    if (mode == SelfCheckMode::Error) throw Error(report.message);
    return report;
}

} // namespace glcollide::engine
