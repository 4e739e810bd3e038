// The contact term of the implicit solve on the GPU (ImplicitSolverPass built with contacts:
// implicit_contact_find/scan/scatter/sort.comp and the GLC_IMPLICIT_CONTACTS variants of the
// solver) against its twin (cpu::implicitContacts, cpu::implicitVelocityUpdate and the dense solve
// of the same system) and against backward Euler's closed form on one contact. The feature-pair
// lists are filled from the host in a chosen order (as the detection's atomic appends would leave
// them in some order), so the determinism test can shuffle them.

#include "cpu/contact_twin.hpp"
#include "cpu/implicit_twin.hpp"
#include "model/features.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/implicit_solver.hpp"
#include "passes/row_layout.hpp"
#include "support/contact_objects.hpp"
#include "support/random_dynamics_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numeric>
#include <random>
#include <tuple>

namespace glcollide {
namespace {

using namespace testing_support;

constexpr double kGravity = 9.81;

/// Free nodes over pinned ones, with faces, ownership and the feature pairs of their face pairs.
struct ContactScene {
    RandomModel model;
    std::vector<std::uint32_t> owned, faceObject;
    std::vector<std::uint8_t> objectClosed;
    cpu::FeaturePairList pairs;

    std::vector<std::uint8_t> faceClosed() const {
        std::vector<std::uint8_t> c;
        for (std::uint32_t o : faceObject) c.push_back(objectClosed[o]);
        return c;
    }
    std::vector<std::uint32_t> nodeObject() const {
        return test::nodeObjectsOfFaces(model.faceIndices, faceObject, model.state.positions.size());
    }
};

void finish(ContactScene& s, const std::vector<cpu::IndexPair>& candidates) {
    RandomModel& m = s.model;
    const auto n = static_cast<std::uint32_t>(m.state.positions.size());
    m.nodeSprings = model::buildSpringAdjacency(n, m.springs);
    m.nodeFaces = model::buildAdjacency(n, m.faceIndices, 3);
    s.owned = model::ownedFeatures(m.faceIndices);
    s.pairs = cpu::featurePairs(m.faceIndices, s.owned, candidates);
}

/// A cloth of n × n free nodes (object 0, open, springs between grid neighbours) turned by 0.35 rad
/// and jittered, 0.15–0.85 of the thickness above a pinned ground grid (object 1, `groundClosed`):
/// vertex-face contacts both ways (cloth vertices on ground faces, ground vertices under cloth
/// faces: rows with negative weights) and edge-edge contacts, none near a rule's threshold.
ContactScene clothOverGround(int n, double thickness, bool groundClosed, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> zeroOne(0.0, 1.0);
    ContactScene s;
    cpu::NodeState& st = s.model.state;
    const double turn = 0.35, spacing = 0.8 / (n - 1);
    const auto addNode = [&](glm::dvec3 x, glm::dvec3 v, double w) {
        st.positions.push_back(glm::dvec3(glm::vec3(x)));
        st.velocities.push_back(glm::dvec3(glm::vec3(v)));
        st.forces.emplace_back(0.0);
        st.inverseMasses.push_back(toFloat(w));
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double a = spacing * i - 0.4 + 0.2 * spacing * (zeroOne(rng) - 0.5);
            const double b = spacing * j - 0.4 + 0.2 * spacing * (zeroOne(rng) - 0.5);
            addNode({0.5 + a * std::cos(turn) - b * std::sin(turn), thickness * (0.15 + 0.7 * zeroOne(rng)),
                     0.5 + a * std::sin(turn) + b * std::cos(turn)},
                    {zeroOne(rng) - 0.5, 0.4 * (zeroOne(rng) - 0.5), zeroOne(rng) - 0.5},
                    1.0 / (0.02 + 0.03 * zeroOne(rng)));
        }
    const int g = 5; // ground grid g × g over [−0.1, 1.1]²
    const auto groundFirst = static_cast<std::uint32_t>(st.positions.size());
    for (int i = 0; i < g; ++i)
        for (int j = 0; j < g; ++j)
            addNode({-0.1 + 1.2 * i / (g - 1), 0.0, -0.1 + 1.2 * j / (g - 1)}, glm::dvec3(0.0), 0.0);
    const auto grid = [&](std::uint32_t first, int size, std::uint32_t object) {
        for (int i = 0; i + 1 < size; ++i)
            for (int j = 0; j + 1 < size; ++j) {
                const auto v = [&](int a, int b) { return first + static_cast<std::uint32_t>(a * size + b); };
                // CCW seen from +y: (i, j), (i, j+1), (i+1, j) has normal +y for x = i, z = j.
                s.model.faceIndices.insert(
                    s.model.faceIndices.end(),
                    {v(i, j), v(i, j + 1), v(i + 1, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)});
                s.faceObject.insert(s.faceObject.end(), {object, object});
            }
    };
    grid(0, n, 0);
    const auto clothFaces = static_cast<std::uint32_t>(s.faceObject.size());
    grid(groundFirst, g, 1);
    s.objectClosed = {0, static_cast<std::uint8_t>(groundClosed ? 1 : 0)};
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto a = static_cast<std::uint32_t>(i * n + j);
            for (const std::uint32_t b : {a + 1, a + static_cast<std::uint32_t>(n)}) {
                if ((b == a + 1 && j + 1 == n) || b >= static_cast<std::uint32_t>(n * n)) continue;
                const double length = glm::length(st.positions[b] - st.positions[a]);
                s.model.springs.push_back(
                    {a, b, toFloat(length), toFloat(50.0 + 50.0 * zeroOne(rng)), 0.01f});
            }
        }
    std::vector<cpu::IndexPair> candidates;
    const auto faces = static_cast<std::uint32_t>(s.faceObject.size());
    for (std::uint32_t a = 0; a < clothFaces; ++a)
        for (std::uint32_t b = clothFaces; b < faces; ++b) candidates.push_back({a, b});
    finish(s, candidates);
    return s;
}

/// Nodes 0–2: a pinned triangle in y = 0 with normal +y; node 3 of mass m at height d above its
/// interior with velocity (0.3, v0, −0.2).
ContactScene nodeOnTriangle(double mass, double d, double v0) {
    ContactScene s;
    cpu::NodeState& st = s.model.state;
    st.positions = {glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0),
                    glm::dvec3(0.25, toFloat(d), 0.25)};
    st.velocities = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0),
                     glm::dvec3(toFloat(0.3), toFloat(v0), toFloat(-0.2))};
    st.forces.assign(4, glm::dvec3(0.0));
    st.inverseMasses = {0.0, 0.0, 0.0, toFloat(1.0 / mass)};
    s.model.faceIndices = {0, 1, 2};
    s.faceObject = {0};
    s.objectClosed = {0};
    finish(s, {});
    s.pairs.vertexFace = {{3, 0}};
    return s;
}

ContactParams contactParams(double thickness, double stiffness) {
    ContactParams p;
    p.thickness = thickness;
    p.stiffness = stiffness;
    return p;
}

ImplicitParams solverParams(double h, bool springs) {
    ImplicitParams p;
    p.h = h;
    p.springs = springs;
    p.external.gravity = true;
    p.external.gravityAcceleration = {0.0, -kGravity, 0.0};
    p.tolerance = 1.0e-6;
    p.maxIterations = 200;
    return p;
}

struct GpuRun {
    std::vector<glm::vec4> velocities; // as the GPU left them (bit comparisons)
    std::vector<gpu::GpuImplicitContact> records;
    std::vector<std::uint32_t> offsets, list;
    std::vector<std::uint8_t> present; // per list slot: 1 where the pair has a record
    std::uint32_t edgeEdgeBase = 0;
    passes::ImplicitSolverCounts counts;
};

/// The GPU's solve of `s` with the lists holding `pairs` in that order (capacity ≥ `capacity`).
/// `newtonStart` (v0): the Newton step instead (ImplicitSolverPass::dispatchNewton) at the state's
/// positions x1 and velocities v1: a first dispatch from v0 records v0, then v1 and x1 (as the
/// predicted positions) are uploaded and the Newton step solves.
GpuRun runGpu(const ContactScene& s, const ImplicitParams& p, const ContactParams& cp,
              const cpu::FeaturePairList& pairs, std::uint32_t capacity = 0, bool contacts = true,
              const std::vector<glm::dvec3>* newtonStart = nullptr) {
    passes::DeviceBuffers b = uploadModel(s.model);
    std::vector<gpu::GpuFaceInfo> info;
    for (std::size_t f = 0; f < s.owned.size(); ++f) info.push_back({s.faceObject[f], 0u, s.owned[f], 0u});
    const std::vector<gpu::GpuObject> objects = test::gpuObjects(s.nodeObject(), s.objectClosed);
    const gl::Buffer faceInfo = upload("faceInfo", info), objectBuffer = upload("objects", objects);
    passes::AppendLists lists(0);
    const auto vf = static_cast<std::uint32_t>(pairs.vertexFace.size());
    const auto ee = static_cast<std::uint32_t>(pairs.edgeEdge.size());
    lists.declare(GLC_LIST_VERTEX_FACE,
                  {"vertexFace", "pairs", 8, GLC_BIND_VERTEX_FACE_PAIRS, std::max({vf, capacity, 1u})});
    lists.declare(GLC_LIST_EDGE_EDGE,
                  {"edgeEdge", "pairs", 8, GLC_BIND_EDGE_EDGE_PAIRS, std::max({ee, capacity, 1u})});
    lists.fillFromHost(GLC_LIST_VERTEX_FACE, pairs.vertexFace.data(), vf);
    lists.fillFromHost(GLC_LIST_EDGE_EDGE, pairs.edgeEdge.data(), ee);
    const std::vector<std::uint32_t> heavy = passes::heavyRowNodes(s.model.nodeSprings.offsets);
    ImplicitParams params = p;
    if (newtonStart) params.newtonSteps = 2;
    passes::ImplicitSolverPass pass(params, b.nodeCount, static_cast<std::uint32_t>(heavy.size()), contacts);
    const passes::ImplicitContacts term{{&lists, &faceInfo, &objectBuffer}, cp};
    if (newtonStart) {
        const std::vector<glm::vec4> v0 = pack(*newtonStart), v1 = pack(s.model.state.velocities);
        b.velocities.upload(0, v0.size() * sizeof(glm::vec4), v0.data());
        pass.dispatch(b, params, &term);
        b.velocities.upload(0, v1.size() * sizeof(glm::vec4), v1.data());
        b.predictedPositions =
            upload("predictedPositions", pack(s.model.state.positions, &s.model.state.inverseMasses));
        pass.dispatchNewton(b, params, term);
    } else {
        pass.dispatch(b, params, contacts ? &term : nullptr);
    }
    GpuRun r;
    r.counts = pass.readStatistics();
    r.velocities.resize(b.nodeCount);
    b.velocities.download(0, r.velocities.size() * sizeof(glm::vec4), r.velocities.data());
    if (!contacts) return r;
    r.edgeEdgeBase = pass.contactEdgeEdgeBase();
    // The GPU appends a record per contact in thread order and keeps its pair's list slot: put
    // them in list-slot order (the twin's; an empty record for a pair that is no contact) and
    // name the incidence entries by slot, so the checks below compare with the twin slot by slot.
    const std::vector<gpu::GpuImplicitContact> appended = pass.downloadContactRecords();
    const std::vector<std::uint32_t> slots = pass.downloadContactRecordSlots();
    r.records.assign(std::size_t{r.edgeEdgeBase} + lists.capacity(GLC_LIST_EDGE_EDGE),
                     gpu::GpuImplicitContact{});
    r.present.assign(r.records.size(), 0);
    for (std::size_t k = 0; k < appended.size(); ++k) {
        EXPECT_LT(slots[k], r.records.size());
        if (slots[k] >= r.records.size()) continue;
        EXPECT_EQ(r.present[slots[k]]++, 0) << "slot " << slots[k] << " has two records";
        r.records[slots[k]] = appended[k];
    }
    r.offsets = pass.downloadNodeContactOffsets();
    r.list = pass.downloadNodeContactList();
    for (std::uint32_t& entry : r.list) entry = 4 * slots.at(entry / 4) + entry % 4;
    return r;
}

std::vector<glm::dvec3> widened(const std::vector<glm::vec4>& v) {
    std::vector<glm::dvec3> out;
    for (const glm::vec4& x : v) out.emplace_back(x.x, x.y, x.z);
    return out;
}

/// The GPU's contact records as the twin's contact set (the same float values, widened).
cpu::ImplicitContactSet gpuContacts(const GpuRun& r, double stiffness) {
    cpu::ImplicitContactSet set;
    set.stiffness = toFloat(stiffness);
    for (std::size_t slot = 0; slot < r.records.size(); ++slot) {
        const gpu::GpuImplicitContact& c = r.records[slot];
        if (!r.present[slot]) continue;
        cpu::ContactGeometry g;
        for (int k = 0; k < 4; ++k) {
            g.nodes[static_cast<std::size_t>(k)] = c.nodes[k];
            g.weights[static_cast<std::size_t>(k)] = c.weights[k];
        }
        g.normal = glm::dvec3(c.normalForce.x, c.normalForce.y, c.normalForce.z);
        g.depth = static_cast<double>(c.normalForce.w) / set.stiffness; // so that k·depth is the GPU's force
        set.contacts.push_back(g);
    }
    return set;
}

double norm(const std::vector<glm::dvec3>& v) {
    double s = 0.0;
    for (const glm::dvec3& x : v) s += glm::dot(x, x);
    return std::sqrt(s);
}

/// The twin's input; `faceClosed` and `nodeObject` (s.faceClosed(), s.nodeObject()) outlive it.
cpu::ContactInput twinInput(const ContactScene& s, const std::vector<std::uint8_t>& faceClosed,
                            const std::vector<std::uint32_t>& nodeObject) {
    cpu::ContactInput in{
        &s.model.state.positions,    &s.model.state.velocities, &s.model.faceIndices, &s.owned, &faceClosed,
        &s.model.state.inverseMasses};
    in.nodeObject = &nodeObject;
    in.faceObject = &s.faceObject;
    return in;
}

/// The largest differences of the GPU's records from the twin's geometry of the same pairs, in
/// units of u (weights: O(1)), of u·L/d for the normal (the closest-point offset of length d
/// carries an error of about u·L; L: the largest coordinate) and of u·k·L for the force k·depth
/// (the depth comes from differences of coordinates up to L).
struct RecordErrors {
    double weights = 0, normal = 0, force = 0;
    std::uint32_t vertexFace = 0, edgeEdge = 0; // records
    std::uint32_t withinMargin = 0;             // of which approaching pairs within the margin (depth 0)
};

// Bounds of RecordErrors: measured on llvmpipe (weights 23.6 u: the edge-edge parameters divide
// by a·e − b², which loses a few bits for edges at 20–40°; normal 1.53 u·L/d; force 0.87 u·k·L),
// then about ×10 for another device's rounding (fused multiply-adds, other operation orders).
constexpr double kWeightErrorUnits = 256.0, kNormalErrorUnits = 16.0, kForceErrorUnits = 8.0;

/// The twin's contacts of one feature pair.
using TwinContacts = std::function<std::vector<cpu::ContactGeometry>(const cpu::FeaturePairList&)>;

/// Every record of `r` against the twin's geometry of its pair (`twinOf`), slot by slot: a record
/// exactly where the twin has a contact, the same nodes, and the largest errors (L: the largest
/// coordinate).
RecordErrors compareRecordsWithTwin(const GpuRun& r, const ContactParams& cp, const TwinContacts& twinOf,
                                    const cpu::FeaturePairList& pairs, double L) {
    RecordErrors e;
    const auto compare = [&](std::uint32_t slot, const cpu::FeaturePairList& one, bool edgeEdge) {
        const std::vector<cpu::ContactGeometry> twin = twinOf(one);
        const gpu::GpuImplicitContact& c = r.records[slot];
        ASSERT_EQ(twin.size(), r.present[slot] ? 1u : 0u) << "slot " << slot;
        if (twin.empty()) return;
        ++(edgeEdge ? e.edgeEdge : e.vertexFace);
        if (!(twin[0].depth > 0.0)) ++e.withinMargin;
        for (int k = 0; k < 4; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            EXPECT_EQ(c.nodes[k], twin[0].nodes[kk]);
            e.weights = std::max(e.weights, std::abs(c.weights[k] - twin[0].weights[kk]) / kUnitRoundoff);
        }
        const glm::dvec3 u(c.normalForce.x, c.normalForce.y, c.normalForce.z);
        // The normal is an offset of length d (or a face's cross product) over its length: its
        // error grows as u·L/d, d the pair's distance, on either side (|h_c − depth|).
        const double d = std::abs(cp.thickness - twin[0].depth);
        ASSERT_GT(d, 0.0);
        e.normal = std::max(e.normal, glm::length(u - twin[0].normal) / (kUnitRoundoff * L / d));
        e.force = std::max(e.force, std::abs(c.normalForce.w - cp.stiffness * twin[0].depth) /
                                        (kUnitRoundoff * cp.stiffness * L));
    };
    for (std::uint32_t i = 0; i < pairs.vertexFace.size(); ++i)
        compare(i, {{pairs.vertexFace[i]}, {}}, false);
    for (std::uint32_t i = 0; i < pairs.edgeEdge.size(); ++i)
        compare(r.edgeEdgeBase + i, {{}, {pairs.edgeEdge[i]}}, true);
    return e;
}

/// compareRecordsWithTwin against cpu::contactGeometries with `crossings`.
RecordErrors compareRecordsWithTwin(const GpuRun& r, const ContactScene& s, const ContactParams& cp,
                                    cpu::Crossings crossings, double L) {
    const std::vector<std::uint8_t> closed = s.faceClosed();
    const std::vector<std::uint32_t> nodeObject = s.nodeObject();
    const cpu::ContactInput in = twinInput(s, closed, nodeObject);
    return compareRecordsWithTwin(
        r, cp,
        [&](const cpu::FeaturePairList& one) { return cpu::contactGeometries(cp, in, one, crossings); },
        s.pairs, L);
}

class ImplicitContactGl : public ::testing::TestWithParam<bool> {}; // the ground is closed

TEST_P(ImplicitContactGl, RecordsAndRowsMatchTheTwin) {
    const ContactScene s = clothOverGround(6, 0.01, GetParam(), 11);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    const ContactParams cp = contactParams(0.01, 1.0e4);
    const GpuRun r = runGpu(s, p, cp, s.pairs);
    const RecordErrors e = compareRecordsWithTwin(r, s, cp, cpu::Crossings::WithinThickness, 1.1);
    std::printf("closed ground %d: %u vertex-face, %u edge-edge contacts; max error: weights %.3g u, normal "
                "%.3g u·L/d, "
                "force %.3g u·k·L\n",
                GetParam() ? 1 : 0, e.vertexFace, e.edgeEdge, e.weights, e.normal, e.force);
    ASSERT_GT(e.vertexFace, 20u);
    ASSERT_GT(e.edgeEdge, 20u);
    EXPECT_LE(e.weights, kWeightErrorUnits);
    EXPECT_LE(e.normal, kNormalErrorUnits);
    EXPECT_LE(e.force, kForceErrorUnits);

    // Every row: exactly the (slot, corner) of the active records with a free node and a weight,
    // sorted by (list, pair, corner): integers, compared exactly.
    const cpu::NodeState& st = s.model.state;
    std::vector<std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>>> rows(
        st.positions.size());
    const auto addRows = [&](std::uint32_t slot, const cpu::IndexPair& pair, std::uint32_t kind) {
        const gpu::GpuImplicitContact& c = r.records[slot];
        for (std::uint32_t k = 0; k < 4; ++k)
            if (r.present[slot] && st.inverseMasses[c.nodes[k]] > 0.0 && c.weights[k] != 0.0f)
                rows[c.nodes[k]].emplace_back(kind, pair[0], pair[1], 4 * slot + k);
    };
    for (std::uint32_t i = 0; i < s.pairs.vertexFace.size(); ++i) addRows(i, s.pairs.vertexFace[i], 0);
    for (std::uint32_t i = 0; i < s.pairs.edgeEdge.size(); ++i)
        addRows(r.edgeEdgeBase + i, s.pairs.edgeEdge[i], 1);
    bool negativeWeightRow = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        std::sort(rows[i].begin(), rows[i].end(), [](const auto& a, const auto& b) {
            return std::make_tuple(std::get<0>(a), std::get<1>(a), std::get<2>(a), std::get<3>(a) % 4) <
                   std::make_tuple(std::get<0>(b), std::get<1>(b), std::get<2>(b), std::get<3>(b) % 4);
        });
        ASSERT_EQ(r.offsets[i + 1] - r.offsets[i], rows[i].size()) << "node " << i;
        for (std::size_t k = 0; k < rows[i].size(); ++k) {
            const std::uint32_t entry = std::get<3>(rows[i][k]);
            EXPECT_EQ(r.list[r.offsets[i] + k], entry) << "node " << i << ", entry " << k;
            negativeWeightRow =
                negativeWeightRow || r.records[entry / 4].weights[static_cast<int>(entry % 4)] < 0.0f;
        }
    }
    EXPECT_TRUE(negativeWeightRow) << "no row of a face's side of a contact: the scene does not test it";
}

/// c of the residual check: as implicit_gl_test.cpp's (tol + c·u)·‖b‖, c = 64.
constexpr double kResidualRoundoffUnits = 64.0;

/// The GPU's solve `r` of `s` against the dense solve of the same system with the GPU's records.
void expectSolveMatchesTheDenseSolve(ContactScene& s, const ImplicitParams& p, const ContactParams& cp,
                                     const GpuRun& r) {
    EXPECT_EQ(r.counts.unconvergedSubsteps, 0u);
    cpu::nodeForce(p.external, s.model.faceIndices, s.model.nodeFaces, s.model.state); // the GPU's f
    const cpu::ImplicitContactSet contacts = gpuContacts(r, cp.stiffness);
    ASSERT_GT(contacts.contacts.size(), 40u);
    const RandomModel& m = s.model;
    const std::vector<glm::dvec3> dvDense =
        cpu::implicitVelocityChangeDense(p, m.springs, m.nodeSprings, m.state, &contacts);
    const std::vector<glm::dvec3> gpu = widened(r.velocities);
    std::vector<glm::dvec3> dvGpu(gpu.size());
    for (std::size_t i = 0; i < gpu.size(); ++i) dvGpu[i] = gpu[i] - m.state.velocities[i];
    const std::vector<glm::dvec3> b =
        cpu::implicitRightHandSide(p, m.springs, m.nodeSprings, m.state, &contacts);
    const auto residual = [&](const std::vector<glm::dvec3>& dv) {
        const std::vector<glm::dvec3> a =
            cpu::implicitSystemProduct(p, m.springs, m.nodeSprings, m.state, dv, &contacts);
        std::vector<glm::dvec3> res(b.size());
        for (std::size_t i = 0; i < b.size(); ++i) res[i] = b[i] - a[i];
        return norm(res);
    };
    const double rGpu = residual(dvGpu), rDense = residual(dvDense), bNorm = norm(b);
    std::printf("%zu contacts, %u iterations, true ‖b − AΔv‖/‖b‖ = %.4g (gap %.3g u), dense %.3g\n",
                contacts.contacts.size(), r.counts.maxIterations, rGpu / bNorm,
                (rGpu / bNorm - r.counts.maxRelativeResidual) / kUnitRoundoff, rDense / bNorm);
    EXPECT_LE(rGpu, (p.tolerance + kResidualRoundoffUnits * kUnitRoundoff) * bNorm);
    // Δv − Δv* = A⁻¹(r − r*), A ⪰ M (springs and contacts are positive semidefinite).
    double maxInverseMass = 0.0, error2 = 0.0;
    for (double w : m.state.inverseMasses) maxInverseMass = std::max(maxInverseMass, w);
    for (std::size_t i = 0; i < gpu.size(); ++i)
        error2 += glm::dot(dvGpu[i] - dvDense[i], dvGpu[i] - dvDense[i]);
    EXPECT_LE(std::sqrt(error2), (rGpu + rDense) * maxInverseMass * (1.0 + 1e-9));
}

TEST_P(ImplicitContactGl, SolveMatchesTheDenseSolveOfTheSameSystem) {
    ContactScene s = clothOverGround(6, 0.01, GetParam(), 12);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    const ContactParams cp = contactParams(0.01, 1.0e4);
    const GpuRun r = runGpu(s, p, cp, s.pairs);
    expectSolveMatchesTheDenseSolve(s, p, cp, r);
}

// Approaching pairs within the margin (ContactParams::solveMargin; decision 0024, "Approaching
// pairs in the solve"): the cloth 0.15–0.85 of 1 cm above the ground, a contact thickness of 5 mm
// and a margin of 5 mm. The pairs closer than 5 mm are contacts; those between 5 and 10 mm get a
// record with force 0 when they approach at the cloth's random velocities and none when they
// recede: every record against the twin's (cpu::implicitContacts), and the solve with those
// records (stiffness without force) against the dense solve of the same system.
TEST_P(ImplicitContactGl, ApproachingPairsWithinTheMarginMatchTheTwin) {
    ContactScene s = clothOverGround(6, 0.01, GetParam(), 15);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    ContactParams cp = contactParams(0.005, 1.0e4);
    cp.solveMargin = 0.005;
    const GpuRun r = runGpu(s, p, cp, s.pairs);
    const std::vector<std::uint8_t> closed = s.faceClosed();
    const std::vector<std::uint32_t> nodeObject = s.nodeObject();
    const cpu::ContactInput in = twinInput(s, closed, nodeObject);
    const RecordErrors e = compareRecordsWithTwin(
        r, cp, [&](const cpu::FeaturePairList& one) { return cpu::implicitContacts(cp, in, one).contacts; },
        s.pairs, 1.1);
    ContactParams band = cp; // every pair within the thickness plus the margin
    band.thickness = cp.thickness + cp.solveMargin;
    band.solveMargin = 0.0;
    const std::size_t inBand = cpu::contactGeometries(band, in, s.pairs, cpu::Crossings::AtAnyDepth).size();
    const std::uint32_t records = e.vertexFace + e.edgeEdge;
    std::printf("closed ground %d: %u records (%u approaching within the margin), %zu receding left out; max "
                "error: weights %.3g u, normal %.3g u·L/d, force %.3g u·k·L\n",
                GetParam() ? 1 : 0, records, e.withinMargin, inBand - records, e.weights, e.normal, e.force);
    EXPECT_GT(records - e.withinMargin, 10u) << "contacts within the thickness";
    EXPECT_GT(e.withinMargin, 10u) << "approaching pairs within the margin";
    EXPECT_GT(inBand - records, 10u) << "receding pairs within the margin, left out";
    EXPECT_LE(e.weights, kWeightErrorUnits);
    EXPECT_LE(e.normal, kNormalErrorUnits);
    EXPECT_LE(e.force, kForceErrorUnits);
    expectSolveMatchesTheDenseSolve(s, p, cp, r);
}

// The Newton step (time.solver.newton_steps 2): the same contacts and matrix at x1, right-hand side
// h·f(x1, v1) − m·(v1 − v0). Its δ against the dense solve of the twin's Newton system, with the
// same residual bound as the first step's.
TEST_P(ImplicitContactGl, NewtonStepMatchesTheDenseSolveOfItsSystem) {
    ContactScene s = clothOverGround(6, 0.01, GetParam(), 14);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    const ContactParams cp = contactParams(0.01, 1.0e4);
    // v0: the state's velocities turned and scaled, so that v1 − v0 is of the order of v1.
    std::vector<glm::dvec3> v0;
    for (const glm::dvec3& v : s.model.state.velocities)
        v0.push_back(glm::dvec3(glm::vec3(glm::dvec3(-0.5 * v.z, 0.8 * v.y - 0.1, 0.5 * v.x))));
    const GpuRun r = runGpu(s, p, cp, s.pairs, 0, true, &v0);
    EXPECT_EQ(r.counts.unconvergedSubsteps, 0u);
    cpu::nodeForce(p.external, s.model.faceIndices, s.model.nodeFaces, s.model.state); // the GPU's f at v1
    const cpu::ImplicitContactSet contacts = gpuContacts(r, cp.stiffness);
    ASSERT_GT(contacts.contacts.size(), 40u);
    const RandomModel& m = s.model;
    const std::vector<glm::dvec3> dDense =
        cpu::implicitNewtonChangeDense(p, m.springs, m.nodeSprings, m.state, v0, &contacts);
    const std::vector<glm::dvec3> gpu = widened(r.velocities);
    std::vector<glm::dvec3> dGpu(gpu.size());
    for (std::size_t i = 0; i < gpu.size(); ++i) dGpu[i] = gpu[i] - m.state.velocities[i];
    const std::vector<glm::dvec3> b =
        cpu::implicitNewtonRightHandSide(p, m.springs, m.nodeSprings, m.state, v0, &contacts);
    const auto residual = [&](const std::vector<glm::dvec3>& d) {
        const std::vector<glm::dvec3> a =
            cpu::implicitSystemProduct(p, m.springs, m.nodeSprings, m.state, d, &contacts);
        std::vector<glm::dvec3> res(b.size());
        for (std::size_t i = 0; i < b.size(); ++i) res[i] = b[i] - a[i];
        return norm(res);
    };
    const double rGpu = residual(dGpu), rDense = residual(dDense), bNorm = norm(b);
    std::printf("Newton, closed ground %d: %zu contacts, true ‖b − Aδ‖/‖b‖ = %.4g, dense %.3g\n",
                GetParam() ? 1 : 0, contacts.contacts.size(), rGpu / bNorm, rDense / bNorm);
    // The first step's bound: tol·‖b‖ plus the float evaluation of b and A·δ (c = 64).
    EXPECT_LE(rGpu, (p.tolerance + kResidualRoundoffUnits * kUnitRoundoff) * bNorm);
    double maxInverseMass = 0.0, error2 = 0.0;
    for (double w : m.state.inverseMasses) maxInverseMass = std::max(maxInverseMass, w);
    for (std::size_t i = 0; i < gpu.size(); ++i) error2 += glm::dot(dGpu[i] - dDense[i], dGpu[i] - dDense[i]);
    EXPECT_LE(std::sqrt(error2), (rGpu + rDense) * maxInverseMass * (1.0 + 1e-9));
}

// A Newton step whose predicted end went through (decision 0024, "Crossings in the Newton
// steps"): the cloth's x1 lies 1.5–4 thicknesses under the ground (x0 = x1 − h·v1: the cloth's
// heights above it). Every record of the Newton step's find against the twin's geometry with
// crossings at any depth (cpu::Crossings::AtAnyDepth), pair by pair; the bounds are the first
// step's, the normal's distance being how far the pair went through.
TEST_P(ImplicitContactGl, NewtonRecordsOfPairsThatWentThroughMatchTheTwin) {
    ContactScene s = clothOverGround(6, 0.01, GetParam(), 15);
    const double h = 1.0 / 60.0;
    const ImplicitParams p = solverParams(h, true);
    ContactParams cp = contactParams(0.01, 1.0e4);
    cp.substep = h; // sides from x1 − h·v1 = x0, as the engine's Newton step
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> under(1.5, 4.0);
    cpu::NodeState& st = s.model.state;
    for (std::size_t i = 0; i < st.positions.size(); ++i) {
        if (st.inverseMasses[i] <= 0.0) continue;
        const double y0 = st.positions[i].y, y1 = toFloat(-cp.thickness * under(rng));
        st.positions[i].y = y1;
        st.velocities[i] = glm::dvec3(0.0, toFloat((y1 - y0) / h), 0.0);
    }
    const std::vector<glm::dvec3> v0 = st.velocities;
    const GpuRun r = runGpu(s, p, cp, s.pairs, 0, true, &v0);
    const RecordErrors e = compareRecordsWithTwin(r, s, cp, cpu::Crossings::AtAnyDepth, 1.1);
    const std::vector<std::uint8_t> closed = s.faceClosed();
    const std::vector<std::uint32_t> nodeObject = s.nodeObject();
    const cpu::ContactInput in = twinInput(s, closed, nodeObject);
    std::uint32_t deep = 0;
    for (const cpu::ContactGeometry& c : cpu::contactGeometries(cp, in, s.pairs, cpu::Crossings::AtAnyDepth))
        deep += c.depth > 2.0 * cp.thickness ? 1u : 0u;
    const auto withinOnly = static_cast<std::uint32_t>(cpu::contactGeometries(cp, in, s.pairs).size());
    std::printf(
        "went through, closed ground %d: %u vertex-face, %u edge-edge contacts (%u deeper than twice the "
        "thickness; %u within it); max error: weights %.3g u, normal %.3g u·L/d, force %.3g u·k·L\n",
        GetParam() ? 1 : 0, e.vertexFace, e.edgeEdge, deep, withinOnly, e.weights, e.normal, e.force);
    ASSERT_GT(e.vertexFace, 20u);
    ASSERT_GT(e.edgeEdge, 20u);
    EXPECT_GT(deep, 20u);
    EXPECT_EQ(withinOnly, 0u)
        << "every cloth node is deeper than the thickness: the responses' rule has none";
    EXPECT_LE(e.weights, kWeightErrorUnits);
    EXPECT_LE(e.normal, kNormalErrorUnits);
    EXPECT_LE(e.force, kForceErrorUnits);
}

INSTANTIATE_TEST_SUITE_P(Ground, ImplicitContactGl, ::testing::Bool(),
                         [](const auto& param) { return param.param ? "Closed" : "Open"; });

// The feature-pair lists are filled by atomic appends, so their order and the records' slots vary
// from run to run: the solve must not. Shuffled lists at another capacity (other slots, another
// edge-edge base) give the same bits.
TEST(ImplicitContactGlDeterminism, ShuffledListsGiveBitIdenticalVelocities) {
    const ContactScene s = clothOverGround(6, 0.01, false, 13);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    const ContactParams cp = contactParams(0.01, 1.0e4);
    const GpuRun a = runGpu(s, p, cp, s.pairs);
    cpu::FeaturePairList shuffled = s.pairs;
    std::mt19937 rng(5);
    std::shuffle(shuffled.vertexFace.begin(), shuffled.vertexFace.end(), rng);
    std::shuffle(shuffled.edgeEdge.begin(), shuffled.edgeEdge.end(), rng);
    const auto capacity =
        static_cast<std::uint32_t>(std::max(s.pairs.vertexFace.size(), s.pairs.edgeEdge.size()) + 77);
    const GpuRun b = runGpu(s, p, cp, shuffled, capacity);
    ASSERT_NE(a.edgeEdgeBase, b.edgeEdgeBase);
    ASSERT_GT(a.list.size(), 100u);
    ASSERT_EQ(a.velocities.size(), b.velocities.size());
    EXPECT_EQ(a.counts.maxIterations, b.counts.maxIterations);
    EXPECT_EQ(std::memcmp(a.velocities.data(), b.velocities.data(), a.velocities.size() * sizeof(glm::vec4)),
              0);
    const GpuRun again = runGpu(s, p, cp, shuffled, capacity);
    EXPECT_EQ(
        std::memcmp(again.velocities.data(), b.velocities.data(), b.velocities.size() * sizeof(glm::vec4)),
        0);
}

// nullptr: the springs-only solve, the same bits from a pass built with contacts as from one without.
TEST(ImplicitContactGlDeterminism, WithoutContactsTheSolveIsTheSpringsOnlySolve) {
    const ContactScene s = clothOverGround(6, 0.01, false, 14);
    const ImplicitParams p = solverParams(1.0 / 30.0, true);
    const ContactParams cp = contactParams(0.01, 1.0e4);
    const GpuRun without = runGpu(s, p, cp, s.pairs, 0, false);
    passes::DeviceBuffers b = uploadModel(s.model);
    passes::ImplicitSolverPass pass(p, b.nodeCount, 0, true);
    pass.dispatch(b, p, nullptr);
    std::vector<glm::vec4> v(b.nodeCount);
    b.velocities.download(0, v.size() * sizeof(glm::vec4), v.data());
    EXPECT_EQ(std::memcmp(v.data(), without.velocities.data(), v.size() * sizeof(glm::vec4)), 0);
    const GpuRun with = runGpu(s, p, cp, s.pairs);
    EXPECT_NE(std::memcmp(with.velocities.data(), without.velocities.data(), v.size() * sizeof(glm::vec4)),
              0);
}

// Backward Euler's closed form on one contact (derivation: tests/unit/implicit_contact_twin_test.cpp):
// v1 = (m·v0 + h·f0)/(m + h²k) along the normal, f0 = −m·g + k·(h_c − d); GPU and twin.
TEST(ImplicitContactGlAnalytic, RestingNodeMatchesBackwardEulerOfOneSpring) {
    const double m = 0.05, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    const ImplicitParams p = solverParams(h, false);
    const ContactParams cp = contactParams(thickness, k);
    for (const double d : {0.002, 0.006, 0.0099})
        for (const double v0 : {0.0, -0.7, 0.4}) {
            ContactScene s = nodeOnTriangle(m, d, v0);
            const GpuRun r = runGpu(s, p, cp, s.pairs);
            const cpu::NodeState& st = s.model.state;
            const double mass = 1.0 / st.inverseMasses[3], y = st.positions[3].y, vy = st.velocities[3].y;
            const double f0 = -mass * kGravity + toFloat(k) * (toFloat(thickness) - y);
            const double expected = (mass * vy + h * f0) / (mass + h * h * toFloat(k));
            // Float: b, the 3×3 block and its inverse, one CG step: each a few operations on terms of
            // at most S = m|v0| + h(m·g + k·h_c) + h²k|v0|, each rounding ≤ u relative; 64u·S/(m + h²k)
            // (the CG stops converged after one step: P is A's only block). Twin: double, 1e-12.
            const double scale =
                (mass * std::abs(vy) + h * (mass * kGravity + k * thickness) + h * h * k * std::abs(vy)) /
                (mass + h * h * k);
            EXPECT_NEAR(r.velocities[3].y, expected, 64.0 * kUnitRoundoff * scale)
                << "d " << d << ", v0 " << v0;
            EXPECT_EQ(r.velocities[3].x, static_cast<float>(st.velocities[3].x));
            EXPECT_EQ(r.counts.maxIterations, 1u);
            cpu::NodeState twin = st;
            cpu::nodeForce(p.external, s.model.faceIndices, s.model.nodeFaces, twin);
            ContactParams twinParams = cp;
            twinParams.stiffness = toFloat(k);
            twinParams.thickness = toFloat(thickness);
            const std::vector<std::uint8_t> closed = s.faceClosed();
            const std::vector<std::uint32_t> nodeObject = s.nodeObject();
            const cpu::ImplicitContactSet contacts =
                cpu::implicitContacts(twinParams, twinInput(s, closed, nodeObject), s.pairs);
            ASSERT_EQ(contacts.contacts.size(), 1u);
            ASSERT_TRUE(cpu::implicitVelocityUpdate(p, {}, s.model.nodeSprings, twin, &contacts).converged);
            EXPECT_NEAR(twin.velocities[3].y, expected, 1e-12 * scale);
        }
}

// A node 1.5 thicknesses above a pinned triangle, falling: the first step (contacts at x0) sees no
// contact and ends at x1 below the triangle. The Newton step finds the contact at x1 (the side from
// x1 − h·v1 = x0: above) and, the penalty being linear in y there, lands on backward Euler's
// closed form with the contact, v* = (m·v0 + h(−m·g + k(h_c − y0)))/(m + h²k), whose y0 + h·v* lies
// inside the thickness: the contact the first step did not see acts in the solve. At 2 m/s x1 is
// 6 thicknesses through the triangle: the Newton step's contacts take crossings at any depth
// (decision 0024, "Crossings in the Newton steps"; without, that x1 had no contact at all).
TEST(ImplicitContactGlAnalytic, NewtonStepCatchesAContactTheFirstStepMissed) {
    const double m = 0.05, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    const ImplicitParams p = solverParams(h, false);
    ContactParams cp = contactParams(thickness, k);
    cp.substep = h;
    for (const double v0 : {-0.2, -0.3, -2.0}) {
        ContactScene s = nodeOnTriangle(m, 1.5 * thickness, v0);
        cpu::NodeState& st = s.model.state;
        const double mass = 1.0 / st.inverseMasses[3], y0 = st.positions[3].y;
        const double vy0 = st.velocities[3].y;
        // The first step as the GPU takes it: no contact at x0, so v1 = v0 − h·g (float).
        const std::vector<glm::dvec3> start = st.velocities;
        st.velocities[3].y = toFloat(vy0 - h * kGravity);
        st.positions[3] = glm::dvec3(glm::vec3(st.positions[3] + h * st.velocities[3]));
        ASSERT_LT(st.positions[3].y, 0.0) << "x1 is through the triangle";
        const GpuRun r = runGpu(s, p, cp, s.pairs, 0, true, &start);
        ASSERT_EQ(r.list.size(), 1u) << "the Newton step finds the contact at x1; v " << r.velocities[3].y
                                     << " x1 " << st.positions[3].x << " " << st.positions[3].y << " "
                                     << st.positions[3].z << " offsets " << r.offsets.size();
        const double kf = toFloat(k), hc = toFloat(thickness);
        const double expected = (mass * vy0 + h * (-mass * kGravity + kf * (hc - y0))) / (mass + h * h * kf);
        ASSERT_LT(y0 + h * expected, hc) << "the closed form's end is inside the thickness";
        // Float: b and the block are a few operations on terms of at most
        // S = m(|v0| + |v1|) + h(m·g + k(h_c + |y1|)), each rounding ≤ u relative; one CG step:
        // 64u·S/(m + h²k), as the resting test's bound.
        const double scale = (mass * (std::abs(vy0) + std::abs(st.velocities[3].y)) +
                              h * (mass * kGravity + kf * (hc + std::abs(st.positions[3].y)))) /
                             (mass + h * h * kf);
        EXPECT_NEAR(r.velocities[3].y, expected, 64.0 * kUnitRoundoff * scale) << "v0 " << v0;
        // The twin's Newton system gives the same closed form (double), up to x1's float storage:
        // y1 carries up to u·|y1| of rounding of y0 + h·v1, which the step carries into v by
        // k·h/(m + h²k) (the closed form assumes y1 = y0 + h·v1 exactly; a clang build's rounding
        // of y1 differed from gcc's by that much), plus the dense solve's 1e-12 relative.
        cpu::NodeState twin = st;
        cpu::nodeForce(p.external, s.model.faceIndices, s.model.nodeFaces, twin);
        ContactParams twinParams = cp;
        twinParams.stiffness = kf;
        twinParams.thickness = hc;
        const std::vector<std::uint8_t> closed = s.faceClosed();
        const std::vector<std::uint32_t> nodeObject = s.nodeObject();
        const cpu::ImplicitContactSet contacts =
            cpu::implicitContacts(twinParams, twinInput(s, closed, nodeObject), s.pairs);
        ASSERT_EQ(contacts.contacts.size(), 1u);
        const std::vector<glm::dvec3> delta =
            cpu::implicitNewtonChangeDense(p, {}, s.model.nodeSprings, twin, start, &contacts);
        const double y1Rounding = std::ldexp(std::abs(st.positions[3].y), -24);
        EXPECT_NEAR(st.velocities[3].y + delta[3].y, expected,
                    kf * h * y1Rounding / (mass + h * h * kf) + 1e-12 * scale);
    }
}

// A node 1.5 thicknesses above a pinned triangle with a margin of one thickness (decision 0024,
// "Approaching pairs in the solve"). Falling, the pair enters the first solve with the stiffness k
// and no force, anchored where it is: backward Euler's closed form along the normal is
// v = (m·v0 − h·m·g)/(m + h²k) — the approach is resisted from x0 on, not only inside the
// thickness. Rising, or at rest (relative velocity 0: not approaching), it is no record and the
// node falls freely, v = v0 − h·g. GPU and twin.
TEST(ImplicitContactGlAnalytic, AnApproachingPairWithinTheMarginGetsStiffnessWithoutForce) {
    const double m = 0.05, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    const ImplicitParams p = solverParams(h, false);
    ContactParams cp = contactParams(thickness, k);
    cp.solveMargin = thickness;
    for (const double v0 : {-0.2, -2.0, 0.0, 0.4}) {
        ContactScene s = nodeOnTriangle(m, 1.5 * thickness, v0);
        const cpu::NodeState& st = s.model.state;
        const double mass = 1.0 / st.inverseMasses[3], vy = st.velocities[3].y, kf = toFloat(k);
        const bool approaching = vy < 0.0;
        const GpuRun r = runGpu(s, p, cp, s.pairs);
        ASSERT_EQ(r.list.size(), approaching ? 1u : 0u) << "v0 " << v0;
        if (approaching) {
            EXPECT_EQ(r.records[0].normalForce.w, 0.0f) << "no force beyond the thickness";
        }
        const double expected =
            approaching ? (mass * vy - h * mass * kGravity) / (mass + h * h * kf) : vy - h * kGravity;
        // Float: as the resting test's bound, 64u·S/(m + h²k) with S = m|v0| + h·m·g + h²k|v0|
        // (without the contact: 64u·(|v0| + h·g)).
        const double scale = approaching
                                 ? (mass * std::abs(vy) + h * mass * kGravity + h * h * kf * std::abs(vy)) /
                                       (mass + h * h * kf)
                                 : std::abs(vy) + h * kGravity;
        EXPECT_NEAR(r.velocities[3].y, expected, 64.0 * kUnitRoundoff * scale) << "v0 " << v0;
        // The twin: the same record (or none) and the same closed form in double.
        cpu::NodeState twin = st;
        cpu::nodeForce(p.external, s.model.faceIndices, s.model.nodeFaces, twin);
        ContactParams twinParams = cp;
        twinParams.stiffness = kf;
        twinParams.thickness = toFloat(thickness);
        twinParams.solveMargin = toFloat(thickness);
        const std::vector<std::uint8_t> closed = s.faceClosed();
        const std::vector<std::uint32_t> nodeObject = s.nodeObject();
        const cpu::ImplicitContactSet contacts =
            cpu::implicitContacts(twinParams, twinInput(s, closed, nodeObject), s.pairs);
        ASSERT_EQ(contacts.contacts.size(), approaching ? 1u : 0u) << "v0 " << v0;
        ASSERT_TRUE(cpu::implicitVelocityUpdate(p, {}, s.model.nodeSprings, twin, &contacts).converged);
        EXPECT_NEAR(twin.velocities[3].y, expected, 1e-12 * scale) << "v0 " << v0;
    }
}

// Restitution between bodies (decision 0024, "Restitution between bodies"): a pair within the
// thickness whose relative normal velocity carries it out of the thickness within the step
// (vn·h ≥ depth) and is a bounce (vn above the resting speed) has no record, so the solve lets it go
// in free flight; the linearised penalty, two-sided, would hold it (v = (m·v0 + h·k·depth −
// h·m·g)/(m + h²k): almost nothing of a 2 m/s bounce at k·h²/m = 222). A slower separation, or one
// the step does not carry out of the thickness, keeps its record. A node 0.8 thicknesses above a
// triangle (depth 2 mm), GPU and twin.
TEST(ImplicitContactGlAnalytic, ABounceLeavingTheThicknessLeavesTheSolve) {
    const double m = 0.05, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01, restingSpeed = 2.0 * kGravity * h;
    const ImplicitParams p = solverParams(h, false);
    ContactParams cp = contactParams(thickness, k);
    cp.leavingStep = h;
    cp.leavingSpeed = restingSpeed;
    for (const double v0 : {2.0, 1.0, 0.3, -0.3}) {
        ContactScene s = nodeOnTriangle(m, 0.8 * thickness, v0);
        const cpu::NodeState& st = s.model.state;
        const double mass = 1.0 / st.inverseMasses[3], vy = st.velocities[3].y, kf = toFloat(k);
        const double depth = thickness - 0.8 * thickness;
        const bool leaves = vy > restingSpeed && vy * h >= depth;
        EXPECT_EQ(leaves, v0 >= 1.0) << "the cases: two bounces, a slow separation, an approach";
        const GpuRun r = runGpu(s, p, cp, s.pairs);
        ASSERT_EQ(r.list.size(), leaves ? 0u : 1u) << "v0 " << v0;
        const double expected =
            leaves ? vy - h * kGravity
                   : (mass * vy + h * kf * depth - h * mass * kGravity) / (mass + h * h * kf);
        // Float: as the test above, 64u·S/(m + h²k) with S = m|v0| + h·k·depth + h·m·g + h²k|v0|
        // (free flight: 64u·(|v0| + h·g)).
        const double scale =
            leaves
                ? std::abs(vy) + h * kGravity
                : (mass * std::abs(vy) + h * kf * depth + h * mass * kGravity + h * h * kf * std::abs(vy)) /
                      (mass + h * h * kf);
        EXPECT_NEAR(r.velocities[3].y, expected, 64.0 * kUnitRoundoff * scale) << "v0 " << v0;
        ContactParams twinParams = cp;
        twinParams.stiffness = kf;
        twinParams.thickness = toFloat(thickness);
        const std::vector<std::uint8_t> closed = s.faceClosed();
        const std::vector<std::uint32_t> nodeObject = s.nodeObject();
        const cpu::ImplicitContactSet contacts =
            cpu::implicitContacts(twinParams, twinInput(s, closed, nodeObject), s.pairs);
        EXPECT_EQ(contacts.contacts.size(), leaves ? 0u : 1u) << "v0 " << v0;
    }
}

// m = 1 kg on k = 10⁴ N/m at h = 1/30 s (h·ω = 3.3, beyond symplectic Euler's limit of 2): at one
// substep per frame the GPU's implicit contact never gains energy (the explicit penalty force
// gains 90× here: tests/unit/implicit_contact_twin_test.cpp).
TEST(ImplicitContactGlAnalytic, StiffContactAtOneSubstepPerFrameNeverGainsEnergy) {
    const double m = 1.0, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    const ImplicitParams p = solverParams(h, false);
    const ContactParams cp = contactParams(thickness, k);
    ContactScene s = nodeOnTriangle(m, 0.008, 0.0);
    s.model.state.velocities[3] = glm::dvec3(0.0);
    const auto energy = [&](const cpu::NodeState& st) {
        const glm::dvec3& x = st.positions[3];
        const double depth = x.y < thickness ? thickness - x.y : 0.0;
        return 0.5 * m * glm::dot(st.velocities[3], st.velocities[3]) + m * kGravity * x.y +
               0.5 * k * depth * depth;
    };
    const double e0 = energy(s.model.state);
    for (int frame = 0; frame < 30; ++frame) {
        const double before = energy(s.model.state);
        const GpuRun r = runGpu(s, p, cp, s.pairs);
        ASSERT_EQ(r.list.size(), 1u) << "frame " << frame << ": the contact holds";
        s.model.state.velocities[3] = widened(r.velocities)[3];
        s.model.state.positions[3] =
            glm::dvec3(glm::vec3(s.model.state.positions[3] + h * s.model.state.velocities[3]));
        // The state is float: y carries u·|y| ≈ 5e-10 m per frame, worth k·h_c·u·|y| + m·g·u·|y| ≈ 6e-9 J;
        // 1e-6·E0 ≈ 1e-7 J covers it 16 times.
        EXPECT_LE(energy(s.model.state), before + 1e-6 * e0) << "frame " << frame;
    }
    EXPECT_LT(energy(s.model.state), 0.96 * e0); // settled: the twin's run ends at 0.947·E0
}

} // namespace
} // namespace glcollide
