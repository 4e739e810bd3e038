#include "benchkit/suite.hpp"

#include "scene/json_errors.hpp"

#include "cpu/oracle/tri_tri_cases.hpp"

#include <glcollide/error.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

namespace glcollide::benchkit {
namespace {

using json = nlohmann::json;

/// Where a value sits: the suite's name and a JSON pointer, for every message.
struct Where {
    const std::string& source;
    std::string pointer;
    [[nodiscard]] Where operator/(const std::string& key) const { return {source, pointer + "/" + key}; }
    [[nodiscard]] Where operator/(std::size_t index) const {
        return {source, pointer + "/" + std::to_string(index)};
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(source + ": " + (pointer.empty() ? "/" : pointer) + ": " + what);
    }
};

void allowOnly(const json& object, const Where& at, std::initializer_list<const char*> keys) {
    if (!object.is_object()) at.fail("expected an object");
    for (const auto& item : object.items()) {
        const std::string& key = item.key(); // not a structured binding: clang 14 cannot capture one
        if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; })) {
            std::string expected;
            for (const char* k : keys) expected += std::string(expected.empty() ? "" : ", ") + k;
            (at / key).fail("unknown key (expected one of: " + expected + ")");
        }
    }
}

std::string stringAt(const json& object, const Where& at, const char* key) {
    if (!object.contains(key)) (at / key).fail("required string is missing");
    const json& v = object.at(key);
    if (!v.is_string() || v.get<std::string>().empty()) (at / key).fail("expected a non-empty string");
    return v.get<std::string>();
}

int intAt(const json& object, const Where& at, const char* key, int fallback, int lo, int hi) {
    if (!object.contains(key)) return fallback;
    const json& v = object.at(key);
    if (!v.is_number_integer()) (at / key).fail("expected an integer");
    const auto n = v.get<long long>();
    if (n < lo || n > hi)
        (at / key).fail("expected an integer in " + std::to_string(lo) + " ... " + std::to_string(hi) +
                        ", got " + std::to_string(n));
    return static_cast<int>(n);
}

json parseJson(const std::string& text, const std::string& source) {
    try {
        return json::parse(text, nullptr, true, true);
    } catch (const json::exception& e) { // parse errors, and numbers beyond double range (1e999)
        throw Error(detail::invalidJsonMessage(e, text, source));
    }
}

std::string readFile(const std::filesystem::path& path, const std::string& what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open " + what);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

ExperimentKind parseKind(const json& experiment, const Where& at) {
    const std::string kind = stringAt(experiment, at, "kind");
    for (ExperimentKind k : {ExperimentKind::Scaling, ExperimentKind::BroadPhase, ExperimentKind::NarrowPhase,
                             ExperimentKind::Integration, ExperimentKind::Contact, ExperimentKind::Bvh,
                             ExperimentKind::Ccd, ExperimentKind::Response})
        if (kind == kindName(k)) return k;
    (at / "kind")
        .fail("unknown kind \"" + kind +
              "\" (expected scaling, broad_phase, narrow_phase, integration, contact, bvh, ccd or response)");
}

/// A scene is inline (an object in the scene format) or a path relative to the suite; either may
/// carry a merge patch.
SceneEntry parseSceneEntry(const json& entry, const Where& at, const std::filesystem::path& baseDir) {
    allowOnly(entry, at, {"name", "scene", "patch"});
    SceneEntry s;
    s.name = stringAt(entry, at, "name");
    if (!entry.contains("scene")) (at / "scene").fail("required scene is missing (an object or a file path)");
    const json& scene = entry.at("scene");
    json document;
    if (scene.is_string()) {
        const std::filesystem::path path = baseDir / scene.get<std::string>();
        document =
            parseJson(readFile(path, "scene file (named at " + (at / "scene").pointer + ")"), path.string());
        s.baseDir = path.parent_path();
        s.source = path.string();
    } else if (scene.is_object()) {
        document = scene;
        s.baseDir = baseDir;
        s.source = at.source + "#" + (at / "scene").pointer;
    } else {
        (at / "scene").fail("expected a scene object or a file path");
    }
    if (entry.contains("patch")) {
        if (!entry.at("patch").is_object()) (at / "patch").fail("expected an object (a JSON merge patch)");
        document.merge_patch(entry.at("patch"));
        s.source += " with " + at.pointer + "/patch";
    }
    s.sceneJson = document.dump();
    return s;
}

ConfigEntry parseConfig(const json& entry, const Where& at) {
    allowOnly(entry, at, {"name", "patch", "substep_factor"});
    ConfigEntry c;
    c.name = stringAt(entry, at, "name");
    if (entry.contains("patch")) {
        if (!entry.at("patch").is_object()) (at / "patch").fail("expected an object (a JSON merge patch)");
        c.patchJson = entry.at("patch").dump();
    }
    c.substepFactor = intAt(entry, at, "substep_factor", 1, 1, 1 << 16);
    return c;
}

template <typename T, typename F>
std::vector<T> parseList(const json& object, const Where& at, const char* key, F parseOne) {
    if (!object.contains(key)) (at / key).fail("required list is missing");
    const json& list = object.at(key);
    if (!list.is_array() || list.empty()) (at / key).fail("expected a non-empty array");
    std::vector<T> out;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
        out.push_back(parseOne(list[i], at / key / i));
        if (!names.insert(out.back().name).second)
            (at / key / i / "name").fail("duplicate name \"" + out.back().name + "\"");
    }
    return out;
}

/// A list of face counts, each in 2 ... 2^26.
std::vector<std::uint32_t> faceCounts(const json& object, const Where& at, const char* key) {
    std::vector<std::uint32_t> counts;
    if (!object.contains(key)) return counts;
    const json& list = object.at(key);
    if (!list.is_array()) (at / key).fail("expected an array of face counts");
    for (std::size_t i = 0; i < list.size(); ++i) {
        if (!list[i].is_number_integer() || list[i].get<long long>() < 2 ||
            list[i].get<long long>() > (1 << 26))
            (at / key / i).fail("expected a face count in 2 ... 67108864");
        counts.push_back(static_cast<std::uint32_t>(list[i].get<long long>()));
    }
    return counts;
}

/// Names of configurations of the experiment (each must exist).
std::vector<std::string> configNames(const json& object, const Where& at, const char* key,
                                     const std::vector<ConfigEntry>& configs) {
    std::vector<std::string> names;
    if (!object.contains(key)) return names;
    const json& list = object.at(key);
    if (!list.is_array()) (at / key).fail("expected an array of configuration names");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = list[i].is_string() ? list[i].get<std::string>() : "";
        if (std::none_of(configs.begin(), configs.end(),
                         [&](const ConfigEntry& c) { return c.name == name; }))
            (at / key / i).fail("not the name of one of this experiment's configs");
        names.push_back(name);
    }
    return names;
}

BvhSpec parseBvhSpec(const json& e, const Where& at, const std::vector<ConfigEntry>& configs) {
    BvhSpec b;
    b.tableFaces = faceCounts(e, at, "table_faces");
    b.scalingFaces = faceCounts(e, at, "scaling_faces");
    b.octreeMaxFaces = static_cast<std::uint32_t>(intAt(e, at, "octree_max_faces", 0, 0, 1 << 26));
    b.slowRunSeconds = intAt(e, at, "slow_run_seconds", 0, 0, 86400);
    b.cpuCheckMaxFaces = static_cast<std::uint32_t>(intAt(e, at, "cpu_check_max_faces", 40000, 0, 1 << 26));
    b.foldLayers = intAt(e, at, "fold_layers", 3, 1, 64);
    if (e.contains("cloth_patch")) {
        if (!e.at("cloth_patch").is_object())
            (at / "cloth_patch").fail("expected an object (a JSON merge patch)");
        b.clothPatch = e.at("cloth_patch").dump();
    }
    b.engineConfigs = configNames(e, at, "engine_configs", configs);
    b.sceneConfigs = configNames(e, at, "scene_configs", configs);
    return b;
}

/// A list of numbers under `key` (integers when `integers`), each in [lo, hi].
std::vector<double> numbersAt(const json& object, const Where& at, const char* key, bool integers, double lo,
                              double hi) {
    std::vector<double> values;
    if (!object.contains(key)) return values;
    const json& list = object.at(key);
    if (!list.is_array()) (at / key).fail("expected an array of numbers");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const bool ok = integers ? list[i].is_number_integer() : list[i].is_number();
        if (!ok || list[i].get<double>() < lo || list[i].get<double>() > hi)
            (at / key / i)
                .fail(std::string("expected ") + (integers ? "an integer" : "a number") + " in " +
                      std::to_string(lo) + " ... " + std::to_string(hi));
        values.push_back(list[i].get<double>());
    }
    return values;
}

constexpr const char* kCcdSetNames[] = {"sample-queries", "sample-queries unit-tests", "cloth-funnel",
                                        "cloth-ball"};

/// Names of CCD query sets under `key` (each one of kCcdSetNames; `allowSample`: the Sample-Queries too).
std::vector<std::string> ccdSetNames(const json& object, const Where& at, const char* key, bool allowSample) {
    std::vector<std::string> names;
    if (!object.contains(key)) return names;
    const json& list = object.at(key);
    if (!list.is_array()) (at / key).fail("expected an array of set names");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = list[i].is_string() ? list[i].get<std::string>() : "";
        const bool known = std::any_of(std::begin(kCcdSetNames), std::end(kCcdSetNames),
                                       [&](const char* n) { return name == n; });
        if (!known || (!allowSample && name.rfind("sample-queries", 0) == 0))
            (at / key / i)
                .fail(allowSample ? "unknown set (expected sample-queries, sample-queries unit-tests, "
                                    "cloth-funnel or cloth-ball)"
                                  : "unknown step (expected cloth-funnel or cloth-ball)");
        names.push_back(name);
    }
    return names;
}

CcdSpec parseCcdSpec(const json& e, const Where& at) {
    CcdSpec c;
    c.sets = ccdSetNames(e, at, "sets", true);
    if (c.sets.empty()) (at / "sets").fail("a ccd experiment needs a non-empty list of query sets");
    for (double b : numbersAt(e, at, "budgets", true, 1, 1 << 24)) c.budgets.push_back(static_cast<int>(b));
    c.minSeparations = numbersAt(e, at, "min_separations", false, 0, 1e30);
    for (double k : numbersAt(e, at, "scale_exponents", true, -100, 100))
        c.scaleExponents.push_back(static_cast<int>(k));
    if (e.contains("peer")) {
        if (!e.at("peer").is_boolean()) (at / "peer").fail("expected true or false");
        c.peer = e.at("peer").get<bool>();
    }
    c.peerTimeoutSeconds = intAt(e, at, "peer_timeout_seconds", c.peerTimeoutSeconds, 1, 86400);
    c.engineSets = ccdSetNames(e, at, "engine_sets", false);
    if (e.contains("engine_thickness")) {
        const json& v = e.at("engine_thickness");
        if (!v.is_number() || !(v.get<double>() > 0))
            (at / "engine_thickness").fail("expected a thickness > 0 (m)");
        c.engineThickness = v.get<double>();
    }
    return c;
}

constexpr const char* kCcdKeys[] = {
    "sets",        "budgets",         "min_separations", "scale_exponents", "peer", "peer_timeout_seconds",
    "engine_sets", "engine_thickness"};

constexpr const char* kResponseNames[] = {"penalty", "bridson", "intersection_free"};

/// The configurations of a response experiment: every response of `responses` at every substep
/// count of `substeps` (the scene's own count when that list is absent). Penalty and bridson run
/// with discrete detection (what they were measured with), intersection_free with continuous
/// detection (the only one it accepts).
std::vector<ConfigEntry> responseConfigs(const json& e, const Where& at) {
    if (e.contains("configs"))
        (at / "configs").fail("a response experiment makes its configs from responses and substeps");
    if (!e.contains("responses")) (at / "responses").fail("required list of responses is missing");
    const json& list = e.at("responses");
    if (!list.is_array() || list.empty()) (at / "responses").fail("expected a non-empty array");
    const std::vector<double> substeps = numbersAt(e, at, "substeps", true, 1, 1000000);
    if (e.contains("substeps") && substeps.empty()) (at / "substeps").fail("expected a non-empty array");
    std::vector<ConfigEntry> configs;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string response = list[i].is_string() ? list[i].get<std::string>() : "";
        if (std::none_of(std::begin(kResponseNames), std::end(kResponseNames),
                         [&](const char* n) { return response == n; }))
            (at / "responses" / i).fail("unknown response (expected penalty, bridson or intersection_free)");
        if (!seen.insert(response).second) (at / "responses" / i).fail("duplicate response");
        // The scene's own detection is removed (a merge patch's null): the response brings its
        // own (detectionOf), as it does in a scene that names none.
        json patch = {{"collision", {{"response", response}, {"detection", nullptr}}}};
        if (substeps.empty()) {
            configs.push_back({response, patch.dump(), 1});
            continue;
        }
        for (std::size_t k = 0; k < substeps.size(); ++k) {
            const int count = static_cast<int>(substeps[k]);
            if (std::count(substeps.begin(), substeps.begin() + static_cast<std::ptrdiff_t>(k), substeps[k]) >
                0)
                (at / "substeps" / k).fail("duplicate substep count");
            patch["time"] = {{"substeps", count}};
            configs.push_back(
                {response + ", " + std::to_string(count) + (count == 1 ? " substep" : " substeps"),
                 patch.dump(), 1});
        }
    }
    return configs;
}

constexpr const char* kBvhKeys[] = {"table_faces",         "scaling_faces",  "octree_max_faces",
                                    "slow_run_seconds",    "fold_layers",    "cloth_patch",
                                    "cpu_check_max_faces", "engine_configs", "scene_configs"};

Experiment parseExperiment(const json& e, const Where& at, const std::filesystem::path& baseDir, int warmup,
                           int frames) {
    allowOnly(e, at,
              {"name",
               "kind",
               "title",
               "scenes",
               "configs",
               "warmup_frames",
               "frames",
               "reference",
               "reference_factor",
               "case_families",
               "table_faces",
               "scaling_faces",
               "octree_max_faces",
               "slow_run_seconds",
               "fold_layers",
               "cloth_patch",
               "cpu_check_max_faces",
               "engine_configs",
               "scene_configs",
               "sets",
               "budgets",
               "min_separations",
               "scale_exponents",
               "peer",
               "peer_timeout_seconds",
               "engine_sets",
               "engine_thickness",
               "responses",
               "substeps"});
    Experiment x;
    x.kind = parseKind(e, at);
    x.name = stringAt(e, at, "name");
    if (x.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
        (at / "name").fail("use lower-case letters, digits, '_' and '-' (it names output files)");
    x.title = e.contains("title") ? stringAt(e, at, "title") : x.name;
    x.warmupFrames = intAt(e, at, "warmup_frames", warmup, 0, 1000);
    x.frames = intAt(e, at, "frames", frames, 1, 100000);
    // A bvh experiment generates its cloths; further scenes are optional.
    // A ccd experiment reads its query sets (no scenes) and has one configuration unless told.
    const bool ccd = x.kind == ExperimentKind::Ccd;
    if (ccd && e.contains("scenes")) (at / "scenes").fail("a ccd experiment has sets, not scenes");
    if (!ccd && (x.kind != ExperimentKind::Bvh || e.contains("scenes")))
        x.scenes = parseList<SceneEntry>(
            e, at, "scenes", [&](const json& s, const Where& w) { return parseSceneEntry(s, w, baseDir); });
    if (ccd && !e.contains("configs"))
        x.configs = {ConfigEntry{"glcollide GPU"}};
    else if (x.kind == ExperimentKind::Response)
        x.configs = responseConfigs(e, at);
    else
        x.configs = parseList<ConfigEntry>(e, at, "configs", parseConfig);
    if (ccd)
        x.ccd = parseCcdSpec(e, at);
    else
        for (const char* key : kCcdKeys)
            if (e.contains(key)) (at / key).fail("only ccd experiments have this key");
    if (x.kind != ExperimentKind::Response)
        for (const char* key : {"responses", "substeps"})
            if (e.contains(key)) (at / key).fail("only response experiments have this key");
    if (x.kind == ExperimentKind::Bvh) {
        x.bvh = parseBvhSpec(e, at, x.configs);
        if (x.bvh.tableFaces.empty() && x.bvh.scalingFaces.empty() && x.scenes.empty())
            at.fail("a bvh experiment needs table_faces, scaling_faces or scenes");
    } else {
        for (const char* key : kBvhKeys)
            if (e.contains(key)) (at / key).fail("only bvh experiments have this key");
    }
    const bool integration = x.kind == ExperimentKind::Integration;
    if (!integration && (e.contains("reference") || e.contains("reference_factor")))
        (at / (e.contains("reference") ? "reference" : "reference_factor"))
            .fail("only integration experiments have a reference");
    if (integration) {
        const std::string ref = e.contains("reference") ? stringAt(e, at, "reference") : "converged";
        if (ref == "converged")
            x.reference = IntegrationReference::Converged;
        else if (ref == "ballistic")
            x.reference = IntegrationReference::Ballistic;
        else if (ref == "oscillator")
            x.reference = IntegrationReference::Oscillator;
        else
            (at / "reference")
                .fail("unknown reference \"" + ref + "\" (expected converged, ballistic or oscillator)");
        x.referenceFactor = intAt(e, at, "reference_factor", 16, 2, 1024);
    }
    if (e.contains("case_families")) {
        if (x.kind != ExperimentKind::NarrowPhase)
            (at / "case_families").fail("only narrow_phase experiments have case families");
        const json& list = e.at("case_families");
        if (!list.is_array()) (at / "case_families").fail("expected an array of family names");
        const std::vector<std::string> known = knownCaseFamilies();
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string name = list[i].is_string() ? list[i].get<std::string>() : "";
            if (std::find(known.begin(), known.end(), name) == known.end()) {
                std::string all;
                for (const std::string& k : known) all += (all.empty() ? "" : ", ") + k;
                (at / "case_families" / i).fail("unknown family (expected one of: " + all + ")");
            }
            x.caseFamilies.push_back(name);
        }
    }
    return x;
}

} // namespace

const char* kindName(ExperimentKind kind) {
    switch (kind) {
    case ExperimentKind::Scaling:
        return "scaling";
    case ExperimentKind::BroadPhase:
        return "broad_phase";
    case ExperimentKind::NarrowPhase:
        return "narrow_phase";
    case ExperimentKind::Integration:
        return "integration";
    case ExperimentKind::Contact:
        return "contact";
    case ExperimentKind::Bvh:
        return "bvh";
    case ExperimentKind::Ccd:
        return "ccd";
    case ExperimentKind::Response:
        return "response";
    }
    return "unknown";
}

std::vector<std::string> knownCaseFamilies() {
    std::vector<std::string> names{"hard"};
    for (cpu::TriTriSet set : cpu::kAllTriTriSets) names.emplace_back(cpu::toString(set));
    return names;
}

Suite parseSuite(const std::string& jsonText, const std::filesystem::path& baseDir,
                 const std::string& sourceName) {
    const json root = parseJson(jsonText, sourceName);
    const Where at{sourceName, ""};
    allowOnly(root, at, {"name", "warmup_frames", "frames", "experiments"});
    Suite suite;
    suite.source = sourceName;
    suite.name = stringAt(root, at, "name");
    const int warmup = intAt(root, at, "warmup_frames", 1, 0, 1000);
    const int frames = intAt(root, at, "frames", 5, 1, 100000);
    suite.experiments = parseList<Experiment>(root, at, "experiments", [&](const json& e, const Where& w) {
        return parseExperiment(e, w, baseDir, warmup, frames);
    });
    return suite;
}

Suite loadSuite(const std::filesystem::path& path) {
    return parseSuite(readFile(path, "suite file"), path.parent_path(), path.string());
}

} // namespace glcollide::benchkit
