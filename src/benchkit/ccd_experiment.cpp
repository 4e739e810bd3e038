#include "benchkit/ccd_experiment.hpp"

#include "cpu/oracle/ccd_query_sets.hpp"
#include "cpu/oracle/ccd_rounding.hpp"
#include "cpu/oracle/exact_ccd.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "model/flat_model.hpp"
#include "passes/ccd_query_pass.hpp"
#include "passes/collision_detection.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace glcollide::benchkit {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using passes::CcdKind;

/// Where the query sets are: $GLCOLLIDE_CCD_DATA, else the source tree's tests/data/external.
fs::path externalDir() {
    if (const char* dir = std::getenv("GLCOLLIDE_CCD_DATA"); dir && *dir) return dir;
    return fs::path(GLCOLLIDE_SOURCE_DIR) / "tests" / "data" / "external";
}

/// Where bench/peers/tight-inclusion/build.sh put the peer: $GLCOLLIDE_TI_DIR, else its default.
fs::path peerDir() {
    if (const char* dir = std::getenv("GLCOLLIDE_TI_DIR"); dir && *dir) return dir;
    return "/tmp/glcollide-peers/tight-inclusion";
}

/// One query set of one kind, with the ground truth of every query.
struct QuerySet {
    std::string name; ///< "sample-queries vf", "cloth-ball ee", ...
    CcdKind kind = CcdKind::VertexFace;
    std::vector<cpu::SampleCcdQuery> queries;
};

std::vector<bool> truthOf(const QuerySet& set) {
    std::vector<bool> truth;
    truth.reserve(set.queries.size());
    for (const auto& q : set.queries) truth.push_back(q.truth);
    return truth;
}

/// Sample-Queries: every CSV under <family>/<vertex-face|edge-edge>/ in path order (all families,
/// or the unit-tests family only).
QuerySet readSampleSet(const fs::path& root, bool unitTestsOnly, CcdKind kind) {
    const std::string folder = kind == CcdKind::VertexFace ? "vertex-face" : "edge-edge";
    std::vector<fs::path> files;
    if (!fs::is_directory(root)) throw Error(root.string() + ": Sample-Queries folder not found");
    for (const auto& family : fs::directory_iterator(root)) {
        if (!family.is_directory()) continue;
        if (unitTestsOnly && family.path().filename() != "unit-tests") continue;
        const fs::path dir = family.path() / folder;
        if (!fs::is_directory(dir)) continue;
        for (const auto& f : fs::directory_iterator(dir))
            if (f.path().extension() == ".csv") files.push_back(f.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw Error(root.string() + ": no " + folder + " query files");
    QuerySet set;
    set.name = std::string(unitTestsOnly ? "sample-queries unit-tests " : "sample-queries ") +
               passes::toString(kind);
    set.kind = kind;
    for (const fs::path& f : files) {
        std::vector<cpu::SampleCcdQuery> q = cpu::readSampleCcdQueries(f.string());
        set.queries.insert(set.queries.end(), std::make_move_iterator(q.begin()),
                           std::make_move_iterator(q.end()));
    }
    return set;
}

/// The named sets, vf then ee.
std::vector<QuerySet> readSets(const std::string& name) {
    const fs::path ext = externalDir();
    std::vector<QuerySet> sets;
    if (name == "sample-queries" || name == "sample-queries unit-tests") {
        for (CcdKind k : {CcdKind::VertexFace, CcdKind::EdgeEdge})
            sets.push_back(readSampleSet(ext / "ccd-sample-queries", name != "sample-queries", k));
        return sets;
    }
    for (const cpu::ScalableCcdSet& s : cpu::scalableCcdSets(ext)) {
        if (s.name.rfind(name + " ", 0) != 0) continue;
        QuerySet set;
        set.name = s.name;
        set.kind = s.kind == cpu::CcdPairKind::VertexFace ? CcdKind::VertexFace : CcdKind::EdgeEdge;
        set.queries = cpu::readScalableCcdQueries(s);
        sets.push_back(std::move(set));
    }
    if (sets.empty())
        throw Error("ccd experiment: no query set named \"" + name + "\" under " + ext.string());
    return sets;
}

/// Every coordinate times 2^k, exactly.
cpu::RationalCcdQuery scaledQuery(cpu::RationalCcdQuery q, int k) {
    for (cpu::RationalPoint& p : q)
        for (mpq_class* c : {&p.x, &p.y, &p.z}) {
            if (k > 0) mpq_mul_2exp(c->get_mpq_t(), c->get_mpq_t(), static_cast<mp_bitcnt_t>(k));
            if (k < 0) mpq_div_2exp(c->get_mpq_t(), c->get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
        }
    return q;
}

/// The float queries the GPU decides, rounded with their rounding covered as `query ccd` does.
std::vector<passes::CcdQuery> roundedQueries(const QuerySet& set, const mpq_class& minSeparation, int scale) {
    std::vector<passes::CcdQuery> out;
    out.reserve(set.queries.size());
    for (const cpu::SampleCcdQuery& q : set.queries) {
        const cpu::RoundedCcdQuery r =
            cpu::roundCcdQuery(scale == 0 ? q.points : scaledQuery(q.points, scale), minSeparation);
        out.push_back({r.points, r.minSeparation});
    }
    return out;
}

/// 1e-4 as an exact decimal rational (the value the suite wrote, not its double).
mpq_class exactDecimal(double v) {
    std::ostringstream s;
    s << std::setprecision(17) << v;
    const std::string text = s.str();
    const auto e = text.find_first_of("eE");
    const std::string mantissa = text.substr(0, e);
    const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
    const auto dot = mantissa.find('.');
    std::string digits = mantissa;
    int fraction = 0;
    if (dot != std::string::npos) {
        digits = mantissa.substr(0, dot) + mantissa.substr(dot + 1);
        fraction = static_cast<int>(mantissa.size() - dot - 1);
    }
    mpq_class value(mpz_class(digits), 1);
    const int ten = exponent - fraction;
    mpz_class power;
    mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(ten)));
    if (ten >= 0)
        value *= power;
    else
        value /= power;
    value.canonicalize();
    return value;
}

/// Three significant digits; "-" for NaN.
std::string num(double v) {
    if (std::isnan(v)) return "-";
    std::ostringstream s;
    const double a = std::abs(v);
    if (a >= 1000)
        s << std::fixed << std::setprecision(0) << v;
    else if (a != 0 && a < 0.01)
        s << std::setprecision(2) << std::scientific << v;
    else
        s << std::setprecision(3) << v;
    return s.str();
}

std::string count(double v) {
    if (std::isnan(v)) return "-";
    std::ostringstream s;
    s << std::fixed << std::setprecision(0) << v;
    return s.str();
}

/// One measurement of our pass on a set: answers, tally, host and GPU time of run() (medians).
struct Ours {
    RunResult run;
    bool ok = false;
    double qpsWall = std::nan(""), qpsGpu = std::nan("");
    CcdTally tally;
    std::uint32_t capped = 0;
};

Ours measureOurs(const Experiment& x, const QuerySet& set, int budget, int rounds, double minSeparation,
                 int scale, bool withTruth, const std::string& scene, const std::string& config) {
    Ours o;
    RunResult& r = o.run;
    r.scene = scene;
    r.config = config;
    r.substeps = 1;
    try {
        const std::vector<passes::CcdQuery> queries = roundedQueries(set, exactDecimal(minSeparation), scale);
        const passes::CcdQueryPass pass(budget, rounds);
        pass.prepare(set.kind); // compiled (or loaded from the program cache) outside the timing
        gl::GpuTimer timer(1);
        std::vector<double> gpu, wall;
        passes::CcdQueryResult result;
        // Warm-up runs first (first use of buffers and the driver's caches), then the measured ones.
        for (int i = 0; i < x.warmupFrames + x.frames; ++i) {
            timer.beginFrame();
            timer.begin(0);
            const auto start = std::chrono::steady_clock::now();
            result = pass.run(set.kind, queries);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            timer.end(0);
            const double gpuMs = timer.resolveMilliseconds()[0];
            if (i < x.warmupFrames) continue;
            gpu.push_back(gpuMs);
            wall.push_back(1e3 * seconds);
        }
        r.passNames = {passes::CcdQueryPass::kName};
        r.passMs = {summarize(gpu)};
        r.gpuMs = summarize(gpu);
        r.wallMs = summarize(wall);
        r.frames = x.frames;
        const double n = static_cast<double>(queries.size());
        o.qpsWall = r.wallMs.median > 0 ? 1e3 * n / r.wallMs.median : std::nan("");
        o.qpsGpu = r.gpuMs.median > 0 ? 1e3 * n / r.gpuMs.median : std::nan("");
        o.capped = result.capped;
        o.tally = tallyCcd(result.mayCollide, truthOf(set));
        r.set("queries", n);
        r.set("positives", static_cast<double>(o.tally.positives));
        if (withTruth) {
            r.set("truth_positives", static_cast<double>(o.tally.truthPositives));
            r.set("false_negatives", static_cast<double>(o.tally.falseNegatives));
            r.set("false_positives", static_cast<double>(o.tally.falsePositives));
        }
        r.set("capped", result.capped);
        r.set("continued", result.continued);
        r.set("boxes", static_cast<double>(result.boxes));
        r.set("budget", budget);
        r.set("continuation_rounds", rounds);
        r.set("min_separation_m", minSeparation);
        r.set("scale_exponent", scale);
        r.set("queries_per_second_wall", o.qpsWall);
        r.set("queries_per_second_gpu", o.qpsGpu);
        r.time = r.wallMs.median;
        r.error = withTruth ? static_cast<double>(o.tally.falseNegatives + o.tally.falsePositives)
                            : static_cast<double>(o.tally.positives);
        o.ok = true;
    } catch (const Error& e) {
        r.failure = e.what();
    }
    return o;
}

/// Tight-Inclusion's answer on one set, as its driver printed it.
struct Peer {
    bool ok = false;
    std::string failure;
    double queries = 0, falseNegatives = 0, falsePositives = 0, positives = 0;
    double seconds = 0, qps = std::nan(""), qpsCpu = std::nan("");
};

std::string shellQuoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

Peer runPeer(const fs::path& driver, const QuerySet& set, const fs::path& csv, int timeoutSeconds,
             bool pinned) {
    Peer p;
    const fs::path errFile = csv.string() + ".stderr";
    std::string command = "timeout " + std::to_string(timeoutSeconds) + " ";
    if (pinned) command += "taskset -c 0 ";
    command += shellQuoted(driver.string()) + " --kind " + passes::toString(set.kind) + " --set " +
               shellQuoted(set.name) + " " + shellQuoted(csv.string()) + " 2>" +
               shellQuoted(errFile.string());
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        p.failure = "cannot start " + driver.string();
        return p;
    }
    std::string output, line;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = pclose(pipe);
    std::istringstream lines(output);
    std::string last;
    while (std::getline(lines, line))
        if (!line.empty() && line.front() == '{') last = line;
    if (status != 0 || last.empty()) {
        std::ifstream err(errFile);
        std::string message;
        std::getline(err, message);
        p.failure =
            driver.filename().string() + " failed (status " + std::to_string(status) +
            (status == 124 * 256 ? ", timed out after " + std::to_string(timeoutSeconds) + " s" : "") + ")" +
            (message.empty() ? "" : ": " + message);
        return p;
    }
    try {
        const json j = json::parse(last);
        p.queries = j.at("queries").get<double>();
        p.positives = j.at("positives").get<double>();
        p.falseNegatives = j.at("false_negatives").get<double>();
        p.falsePositives = j.at("false_positives").get<double>();
        p.seconds = j.at("seconds").get<double>();
        p.qps = j.at("queries_per_second").get<double>();
        p.qpsCpu = j.at("queries_per_cpu_second").get<double>();
        p.ok = true;
    } catch (const json::exception& e) {
        p.failure = driver.filename().string() + ": unreadable output (" + e.what() + ")";
    }
    return p;
}

RunResult peerRun(const Peer& p, const std::string& scene, const std::string& config) {
    RunResult r;
    r.scene = scene;
    r.config = config;
    r.substeps = 1;
    r.frames = 1;
    if (!p.ok) {
        r.failure = p.failure;
        return r;
    }
    r.wallMs = summarize({1e3 * p.seconds});
    r.set("queries", p.queries);
    r.set("positives", p.positives);
    r.set("false_negatives", p.falseNegatives);
    r.set("false_positives", p.falsePositives);
    r.set("queries_per_second_wall", p.qps);
    r.set("queries_per_cpu_second", p.qpsCpu);
    r.set("peer", 1);
    r.time = 1e3 * p.seconds;
    r.error = p.falseNegatives + p.falsePositives;
    return r;
}

std::string fnFp(const CcdTally& t) {
    return std::to_string(t.falseNegatives) + " / " + std::to_string(t.falsePositives);
}

/// The per-set table: ours beside Tight-Inclusion (double, float) and the measured ratio.
void querySets(const Experiment& x, ExperimentResult& out, const Progress& progress,
               const std::vector<QuerySet>& sets) {
    const fs::path dir = peerDir();
    const fs::path drivers[2] = {dir / "bin" / "ti_queries_double", dir / "bin" / "ti_queries_float"};
    const bool peerBuilt = fs::exists(drivers[0]) && fs::exists(drivers[1]);
    const bool pinned = std::system("command -v taskset >/dev/null 2>&1") == 0;
    std::optional<fs::path> tmp;
    if (x.ccd.peer && peerBuilt) {
        tmp = fs::temp_directory_path() / ("glcollide-ccd-peer-" + std::to_string(getpid()));
        fs::create_directories(*tmp);
        std::string version = "unknown version";
        std::ifstream commit(dir / "source-commit.txt");
        std::getline(commit, version);
        out.notes.push_back("Tight-Inclusion (" + version +
                            ", built by bench/peers/tight-inclusion/build.sh in " + dir.string() +
                            ") ran on the same queries in this run, " +
                            (pinned ? "pinned to core 0 (taskset -c 0)" : "NOT pinned (taskset missing)") +
                            ", with its benchmark's settings (minimum separation 0, tolerance 1e-6, 10^6 "
                            "iterations); its q/s is wall clock of its loop of CCD calls, parsing excluded.");
    } else if (x.ccd.peer) {
        out.notes.push_back("Tight-Inclusion: peer not available (no " + drivers[0].string() + " and " +
                            drivers[1].filename().string() +
                            "; set GLCOLLIDE_TI_DIR or run bench/peers/tight-inclusion/build.sh). No "
                            "peer numbers and no ratio in this run.");
    } else {
        out.notes.push_back("Tight-Inclusion: not run (the suite turns the peer off).");
    }
    SummaryTable table;
    table.title = "CCD query sets: glcollide GPU (default budget " +
                  std::to_string(passes::kDefaultCcdBudget) + ", " +
                  std::to_string(passes::kDefaultCcdContinuationRounds) +
                  " continuation rounds) beside Tight-Inclusion on one CPU core";
    table.header = {"set",
                    "queries (collide)",
                    "ours FN / FP",
                    "ours capped",
                    "ours q/s (run() wall)",
                    "ours q/s (GPU timestamps)",
                    "TI double FN / FP",
                    "TI double q/s",
                    "TI float FN / FP",
                    "TI float q/s",
                    "ours / TI double (q/s, wall)"};
    for (const QuerySet& set : sets) {
        progress(set.name + " / glcollide GPU");
        Ours ours = measureOurs(x, set, passes::kDefaultCcdBudget, passes::kDefaultCcdContinuationRounds, 0.0,
                                0, true, set.name, "glcollide GPU");
        std::vector<std::string> row = {set.name,
                                        std::to_string(set.queries.size()) + " (" +
                                            std::to_string(ours.tally.truthPositives) + ")",
                                        ours.ok ? fnFp(ours.tally) : "failed",
                                        ours.ok ? std::to_string(ours.capped) : "-",
                                        num(ours.qpsWall),
                                        num(ours.qpsGpu)};
        std::optional<fs::path> csv;
        if (tmp) {
            csv = *tmp / (std::to_string(&set - sets.data()) + ".csv");
            cpu::writeSampleCcdQueries(csv->string(), set.queries);
        }
        double ratio = std::nan("");
        for (int precision = 0; precision < 2; ++precision) {
            const std::string config =
                precision == 0 ? "Tight-Inclusion double (1 core)" : "Tight-Inclusion float (1 core)";
            if (!csv) {
                row.insert(row.end(), {"-", "-"});
                continue;
            }
            progress(set.name + " / " + config);
            const Peer p = runPeer(drivers[precision], set, *csv, x.ccd.peerTimeoutSeconds, pinned);
            RunResult pr = peerRun(p, set.name, config);
            if (p.ok && ours.ok) {
                pr.set("ours_per_peer_qps", ours.qpsWall / p.qps);
                if (precision == 0) ratio = ours.qpsWall / p.qps;
            }
            out.runs.push_back(pr);
            row.push_back(p.ok ? count(p.falseNegatives) + " / " + count(p.falsePositives) : "failed");
            row.push_back(p.ok ? num(p.qps) : "-");
        }
        if (!std::isnan(ratio)) ours.run.set("ours_per_ti_double_qps", ratio);
        row.push_back(num(ratio));
        out.runs.insert(out.runs.end() - (csv ? 2 : 0), ours.run);
        table.rows.push_back(row);
    }
    if (tmp) fs::remove_all(*tmp);
    out.tables.push_back(table);
}

/// Budget, minimum separation and 2^k scaling on `sets` (the first named set, vf and ee).
void sweeps(const Experiment& x, ExperimentResult& out, const Progress& progress,
            const std::vector<QuerySet>& sets) {
    const int rounds = passes::kDefaultCcdContinuationRounds;
    if (!x.ccd.budgets.empty()) {
        SummaryTable t;
        t.title = "Accuracy against cost: budget (boxes per query and piece, " + std::to_string(rounds) +
                  " continuation rounds), minimum separation 0";
        t.header = {"set", "budget", "FN / FP", "capped", "run() wall ms", "GPU ms", "q/s (wall)"};
        for (const QuerySet& set : sets)
            for (int b : x.ccd.budgets) {
                progress(set.name + " / budget " + std::to_string(b));
                Ours o = measureOurs(x, set, b, rounds, 0.0, 0, true, set.name + " (sweep)",
                                     "budget " + std::to_string(b));
                o.run.set("sweep", 1);
                t.rows.push_back({set.name, std::to_string(b),
                                  o.ok ? fnFp(o.tally) : "failed: " + o.run.failure,
                                  o.ok ? std::to_string(o.capped) : "-", num(o.run.wallMs.median),
                                  num(o.run.gpuMs.median), num(o.qpsWall)});
                out.runs.push_back(o.run);
            }
        out.tables.push_back(t);
    }
    if (!x.ccd.minSeparations.empty()) {
        SummaryTable t;
        t.title = "Accuracy against cost: minimum separation (default budget; above 0 there is no ground "
                  "truth: positives only)";
        t.header = {"set",    "min separation (m)", "positives", "FN / FP (separation 0 only)",
                    "capped", "run() wall ms",      "q/s (wall)"};
        for (const QuerySet& set : sets)
            for (double d : x.ccd.minSeparations) {
                progress(set.name + " / min separation " + num(d));
                Ours o = measureOurs(x, set, passes::kDefaultCcdBudget, rounds, d, 0, d == 0,
                                     set.name + " (sweep)", "min separation " + num(d) + " m");
                o.run.set("sweep", 1);
                t.rows.push_back({set.name, num(d),
                                  o.ok ? std::to_string(o.tally.positives) : "failed: " + o.run.failure,
                                  o.ok && d == 0 ? fnFp(o.tally) : "-", o.ok ? std::to_string(o.capped) : "-",
                                  num(o.run.wallMs.median), num(o.qpsWall)});
                out.runs.push_back(o.run);
            }
        out.tables.push_back(t);
    }
    if (!x.ccd.scaleExponents.empty()) {
        SummaryTable t;
        t.title = "Every coordinate times 2^k (ground truth unchanged), default budget";
        t.header = {"set", "k", "FN / FP", "capped", "run() wall ms"};
        for (const QuerySet& set : sets)
            for (int k : x.ccd.scaleExponents) {
                progress(set.name + " / scaled 2^" + std::to_string(k));
                Ours o = measureOurs(x, set, passes::kDefaultCcdBudget, rounds, 0.0, k, true,
                                     set.name + " (scaled)", "2^" + std::to_string(k));
                o.run.set("sweep", 1);
                t.rows.push_back({set.name, std::to_string(k),
                                  o.ok ? fnFp(o.tally) : "failed: " + o.run.failure,
                                  o.ok ? std::to_string(o.capped) : "-", num(o.run.wallMs.median)});
                out.runs.push_back(o.run);
            }
        out.tables.push_back(t);
    }
}

/// A step's mesh as one self-colliding object at its start frame.
model::FlatModel stepModel(const cpu::CcdStep& step) {
    model::FlatModel m;
    m.positions = step.start;
    for (const cpu::MeshFace& f : step.faces) m.faceIndices.insert(m.faceIndices.end(), f.begin(), f.end());
    model::ObjectRange r;
    r.nodeCount = static_cast<std::uint32_t>(m.positions.size());
    r.faceCount = static_cast<std::uint32_t>(step.faces.size());
    m.objects.push_back(r);
    m.velocities.assign(m.positions.size(), glm::dvec3(0.0));
    m.masses.assign(m.positions.size(), 1.0);
    m.inverseMasses.assign(m.positions.size(), 1.0);
    return m;
}

gl::Buffer vec4Buffer(const char* label, const std::vector<glm::dvec3>& points) {
    std::vector<glm::vec4> packed;
    packed.reserve(points.size());
    for (const glm::dvec3& p : points) packed.emplace_back(glm::vec3(p), 1.0f);
    return gl::makeBuffer(label, packed);
}

/// One detection of a whole step, continuous (positions = start, predicted = end) or discrete
/// (positions = start), BVH broad phase: per-pass GPU medians and the last detection's counts.
RunResult measureStep(const Experiment& x, const std::string& scene, const cpu::CcdStep& step,
                      bool continuous) {
    RunResult r;
    r.scene = scene;
    r.config = continuous ? "swept (continuous)" : "discrete";
    r.substeps = 1;
    try {
        const model::FlatModel model = stepModel(step);
        r.nodes = static_cast<std::uint32_t>(model.nodeCount());
        r.faces = static_cast<std::uint32_t>(model.faceCount());
        passes::CollisionConfig config;
        config.selfCollisions = true;
        config.settings.broadPhase = BroadPhase::Bvh;
        config.settings.thickness = x.ccd.engineThickness;
        config.settings.initialCapacity = 1u << 16;
        config.settings.detection = continuous ? Detection::Continuous : Detection::Discrete;
        passes::CollisionDetection detection(config, model);
        passes::DeviceBuffers buffers;
        buffers.nodeCount = r.nodes;
        buffers.faceCount = r.faces;
        buffers.positions = vec4Buffer("positions", step.start);
        buffers.faces = gl::makeBuffer("faces", model.faceIndices);
        if (continuous) buffers.predictedPositions = vec4Buffer("predictedPositions", step.end);
        const std::vector<passes::PassId> ids = detection.passes();
        r.passNames = detection.passNames();
        std::vector<std::vector<double>> samples(ids.size());
        std::vector<double> total, wall;
        gl::GpuTimer timer(passes::kPassCount);
        // One warm-up (list growth, first use), then x.frames timed, or one when the warm-up took
        // over 10 s (llvmpipe on cloth-ball's swept detection).
        int timed = x.frames;
        for (int i = 0; i < 1 + timed; ++i) {
            const auto start = std::chrono::steady_clock::now();
            timer.beginFrame();
            detection.detect(buffers, &timer);
            const std::vector<double> t = timer.resolveMilliseconds();
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (i == 0) {
                if (seconds > 10.0) timed = 1;
                continue;
            }
            double sum = 0.0;
            for (std::size_t p = 0; p < ids.size(); ++p) {
                samples[p].push_back(t[passes::passIndex(ids[p])]);
                sum += t[passes::passIndex(ids[p])];
            }
            total.push_back(sum);
            wall.push_back(1e3 * seconds);
        }
        for (auto& s : samples) r.passMs.push_back(summarize(s));
        r.gpuMs = summarize(total);
        r.wallMs = summarize(wall);
        r.frames = static_cast<int>(total.size());
        const passes::CollisionCounts& c = detection.lastCounts();
        r.set("candidate_pairs", c.candidates);
        r.set("vf_pairs_gpu", c.vertexFacePairs);
        r.set("ee_pairs_gpu", c.edgeEdgePairs);
        r.set("intersecting_pairs", c.intersections);
        if (continuous) {
            r.set("ccd_vf_hits", c.ccdVertexFaceHits);
            r.set("ccd_ee_hits", c.ccdEdgeEdgeHits);
            r.set("ccd_capped", c.ccdCapped);
            r.set("ccd_boxes", c.ccdBoxes);
            r.set("ccd_budget", config.settings.ccd.budget);
        }
        r.set("thickness_m", x.ccd.engineThickness);
        r.set("engine_workload", 1);
        r.time = r.gpuMs.median;
    } catch (const Error& e) {
        r.failure = e.what();
    }
    return r;
}

double passMs(const RunResult& r, passes::PassId id) {
    for (std::size_t p = 0; p < r.passNames.size() && p < r.passMs.size(); ++p)
        if (r.passNames[p] == passes::passName(id)) return r.passMs[p].median;
    return std::nan("");
}

void engineWorkload(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    if (x.ccd.engineSets.empty()) return;
    SummaryTable t;
    t.title = "Engine workload: one detection of a whole step as one self-colliding object, BVH broad "
              "phase, thickness " +
              num(x.ccd.engineThickness) + " m (GPU ms, medians)";
    t.header = {"step",
                "faces",
                "detection",
                "GPU ms",
                "wall ms",
                "BVH (build+refit+traverse)",
                "TriTri",
                "FeaturePairs",
                "Ccd",
                "candidates",
                "feature pairs (vf + ee)",
                "CCD hits (vf + ee)",
                "capped",
                "swept / discrete"};
    for (const std::string& name : x.ccd.engineSets) {
        std::optional<cpu::ScalableCcdSet> found;
        for (const cpu::ScalableCcdSet& s : cpu::scalableCcdSets(externalDir()))
            if (s.name.rfind(name + " ", 0) == 0) found = s;
        if (!found) throw Error("ccd experiment: no step named \"" + name + "\"");
        const cpu::CcdStep step = cpu::readCcdStep(found->startFrame, found->endFrame);
        const std::string scene = name + " " + found->startFrame.stem().string() + " -> " +
                                  found->endFrame.stem().string() + " (step)";
        RunResult runs[2];
        for (int continuous = 1; continuous >= 0; --continuous) {
            progress(scene + (continuous ? " / swept" : " / discrete"));
            runs[continuous] = measureStep(x, scene, step, continuous == 1);
        }
        const double ratio = runs[1].failure.empty() && runs[0].failure.empty() && runs[0].gpuMs.median > 0
                                 ? runs[1].gpuMs.median / runs[0].gpuMs.median
                                 : std::nan("");
        for (int continuous = 1; continuous >= 0; --continuous) {
            RunResult& r = runs[continuous];
            if (!r.failure.empty()) {
                t.rows.push_back({scene, "-", r.config, "failed: " + r.failure});
                out.runs.push_back(r);
                continue;
            }
            double bvh = 0.0;
            for (auto id : {passes::PassId::BvhBuild, passes::PassId::BvhRefit, passes::PassId::BvhTraverse})
                if (const double v = passMs(r, id); !std::isnan(v)) bvh += v;
            if (continuous) r.set("swept_per_discrete_gpu", ratio);
            t.rows.push_back(
                {scene, std::to_string(r.faces), r.config, num(r.gpuMs.median), num(r.wallMs.median),
                 num(bvh), num(passMs(r, passes::PassId::TriTri)),
                 num(passMs(r, passes::PassId::FeaturePairs)), num(passMs(r, passes::PassId::Ccd)),
                 count(r.metric("candidate_pairs")),
                 count(r.metric("vf_pairs_gpu")) + " + " + count(r.metric("ee_pairs_gpu")),
                 continuous ? count(r.metric("ccd_vf_hits")) + " + " + count(r.metric("ccd_ee_hits")) : "-",
                 continuous ? count(r.metric("ccd_capped")) : "-", continuous ? num(ratio) : "1"});
            out.runs.push_back(r);
        }
    }
    out.tables.push_back(t);
    out.notes.push_back("Engine workload: passes::CollisionDetection::detect() on the step's start frame "
                        "(discrete) or from its start to its end frame (swept: swept boxes, feature pairs, "
                        "vertex-face and edge-edge CCD with the engine's default budget), self-collisions of "
                        "one object, BVH broad phase, one warm-up detection then the measured ones (one when "
                        "the warm-up took over 10 s).");
}

} // namespace

CcdTally tallyCcd(const std::vector<std::uint8_t>& answers, const std::vector<bool>& truth) {
    if (answers.size() != truth.size())
        throw Error("ccd experiment: " + std::to_string(answers.size()) + " answers for " +
                    std::to_string(truth.size()) + " queries");
    CcdTally t;
    t.queries = answers.size();
    for (std::size_t i = 0; i < answers.size(); ++i) {
        const bool answer = answers[i] != 0;
        t.truthPositives += truth[i] ? 1 : 0;
        t.positives += answer ? 1 : 0;
        t.falseNegatives += truth[i] && !answer ? 1 : 0;
        t.falsePositives += !truth[i] && answer ? 1 : 0;
    }
    return t;
}

std::size_t ccdRunCount(const Experiment& x) {
    const std::size_t sets = 2 * x.ccd.sets.size();
    const std::size_t sweep =
        2 * (x.ccd.budgets.size() + x.ccd.minSeparations.size() + x.ccd.scaleExponents.size());
    return sets * (x.ccd.peer ? 3 : 1) + sweep + 2 * x.ccd.engineSets.size();
}

void runCcdExperiment(const Experiment& x, ExperimentResult& out, const Progress& progress) {
    out.timeLabel = "wall ms per query set";
    out.errorLabel = "false negatives + false positives";
    out.errorIsCount = true;
    std::vector<QuerySet> all;
    std::vector<QuerySet> first; // the first named set (vf, ee): the sweeps run on it
    for (const std::string& name : x.ccd.sets) {
        std::vector<QuerySet> sets = readSets(name);
        if (first.empty()) first = sets;
        all.insert(all.end(), sets.begin(), sets.end());
    }
    querySets(x, out, progress, all);
    sweeps(x, out, progress, first);
    engineWorkload(x, out, progress);
    out.notes.push_back(
        "Queries per second of ours: the queries over the host wall time of one "
        "CcdQueryPass::run() (upload, dispatches, continuation rounds, read-back; rounding "
        "the rationals to floats excluded), median of the measured runs; the GPU column "
        "brackets the same call with timestamps. FN / FP count against each set's ground truth.");
}

} // namespace glcollide::benchkit
