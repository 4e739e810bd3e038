// The contact term of the implicit twin (cpu::implicitVelocityUpdate with an ImplicitContactSet)
// against analytic answers: one free node resting within the thickness above a pinned triangle is
// a 1-D spring in the normal direction, whose backward Euler step has a closed form; at one
// substep per frame the implicit contact loses energy where the explicit penalty force gains it;
// and the contact blocks keep A symmetric positive definite.

#include "cpu/contact_twin.hpp"
#include "cpu/implicit_twin.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace glcollide {
namespace {

constexpr std::uint32_t kOwnAll =
    GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2 | GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20;
constexpr double kGravity = 9.81;

/// Nodes 0–2: a pinned triangle in the plane y = 0, normal +y (CCW seen from above); node 3 of mass
/// m at (0.25, y, 0.25), above the triangle's interior.
struct NodeOnTriangle {
    cpu::NodeState state;
    std::vector<std::uint32_t> faces{0, 1, 2}, owned{kOwnAll};
    std::vector<std::uint8_t> closed{0}; // an open sheet: the side is the node's side (substep 0)
    // The node is another object's (closed: it is kept outside the face).
    std::vector<std::uint32_t> nodeObject{0, 0, 0, 1}, faceObject{0};
    cpu::FeaturePairList pairs{{{3, 0}}, {}};

    NodeOnTriangle(double mass, double height, double verticalSpeed) {
        state.positions = {glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0),
                           glm::dvec3(0.25, height, 0.25)};
        state.velocities = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0),
                            glm::dvec3(0.3, verticalSpeed, -0.2)};
        state.inverseMasses = {0.0, 0.0, 0.0, 1.0 / mass};
        state.forces = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0),
                        glm::dvec3(0, -mass * kGravity, 0)};
    }
    cpu::ContactInput input() const {
        cpu::ContactInput in{&state.positions, &state.velocities, &faces,
                             &owned,           &closed,           &state.inverseMasses};
        in.nodeObject = &nodeObject;
        in.faceObject = &faceObject;
        return in;
    }
    cpu::ImplicitContactSet contacts(const ContactParams& p) const {
        return cpu::implicitContacts(p, input(), pairs);
    }
};

ContactParams contactParams(double thickness, double stiffness) {
    ContactParams p;
    p.thickness = thickness;
    p.stiffness = stiffness;
    p.forceCap = 4.0 * stiffness * thickness; // what contactParams(CollisionSettings) derives
    return p;
}

ImplicitParams implicitParams(double h) {
    ImplicitParams p;
    p.h = h;
    p.tolerance = 1e-14;
    p.maxIterations = 50;
    return p;
}

// Backward Euler on m·v' = f(x), linearised at x0 (one Newton step): m(v1 − v0) = h·f(x0 + h·v1)
// ≈ h·(f0 − k·h·v1) along the normal, with f0 = −m·g + k·(h_c − d) and ∂f/∂x = −k. So
// (m + h²k)·v1 = m·v0 + h·f0 and v1 = (m·v0 + h·f0)/(m + h²k) = (v0 + h·f0/m)/(1 + h²k/m).
// (Not (v0 + h·(f0/m − h·k·v0/m))/(1 + h²k/m): that counts −h²k·v0 twice; the two agree at v0 = 0.)
double backwardEulerNormalSpeed(double m, double k, double h, double thickness, double d, double v0) {
    const double f0 = -m * kGravity + k * (thickness - d);
    return (m * v0 + h * f0) / (m + h * h * k);
}

TEST(ImplicitContactTwin, RestingNodeMatchesBackwardEulerOfOneSpring) {
    const double m = 0.05, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    for (const double d : {0.002, 0.006, 0.0099})
        for (const double v0 : {0.0, -0.7, 0.4}) {
            NodeOnTriangle s(m, d, v0);
            const cpu::ImplicitContactSet contacts = s.contacts(contactParams(thickness, k));
            ASSERT_EQ(contacts.contacts.size(), 1u);
            const cpu::ImplicitSolveStats stats = cpu::implicitVelocityUpdate(
                implicitParams(h), {}, model::Csr{{0, 0, 0, 0, 0}, {}}, s.state, &contacts);
            EXPECT_TRUE(stats.converged);
            const double expected = backwardEulerNormalSpeed(m, k, h, thickness, d, v0);
            // Double arithmetic on numbers of at most |m·v0| + h·|f0| + h²k|v0|: 1e-12 relative.
            const double scale = (m * std::abs(v0) + h * (m * kGravity + k * thickness)) / (m + h * h * k);
            EXPECT_NEAR(s.state.velocities[3].y, expected, 1e-12 * scale) << "d " << d << ", v0 " << v0;
            EXPECT_EQ(s.state.velocities[3].x, 0.3); // no force across the normal: untouched
            EXPECT_EQ(s.state.velocities[3].z, -0.2);
            for (int i = 0; i < 3; ++i)
                EXPECT_EQ(s.state.velocities[static_cast<std::size_t>(i)], glm::dvec3(0.0));
        }
}

/// Kinetic, gravity and penalty energy of the node (the penalty's ½k·depth² within the thickness).
double energy(const NodeOnTriangle& s, double k, double thickness) {
    const glm::dvec3& x = s.state.positions[3];
    const double m = 1.0 / s.state.inverseMasses[3];
    const double depth = x.y < thickness && x.y > -thickness ? thickness - x.y : 0.0;
    return 0.5 * m * glm::dot(s.state.velocities[3], s.state.velocities[3]) + m * kGravity * x.y +
           0.5 * k * depth * depth;
}

// m = 1 kg on k = 10⁴ N/m: ω = 100/s, and h = 1/30 s gives h·ω = 3.3 > 2, beyond symplectic
// Euler's stability limit. Starting 2 mm deep at rest, the explicit penalty force throws the node
// out (E: 0.098 J → 0.25 J in the first frame, 9 J once it falls back through the thickness);
// backward Euler is dissipative for a linear spring (|1/(1 + i·h·ω)| < 1) and keeps the contact.
TEST(ImplicitContactTwin, StiffContactAtOneSubstepPerFrameLosesEnergyWhereThePenaltyGainsIt) {
    const double m = 1.0, k = 1.0e4, h = 1.0 / 30.0, thickness = 0.01;
    const ContactParams p = contactParams(thickness, k);
    NodeOnTriangle implicit(m, 0.008, 0.0), explicitNode(m, 0.008, 0.0);
    implicit.state.velocities[3] = explicitNode.state.velocities[3] = glm::dvec3(0.0);
    const double e0 = energy(implicit, k, thickness);
    double explicitMax = e0;
    for (int frame = 0; frame < 30; ++frame) {
        const double before = energy(implicit, k, thickness);
        const cpu::ImplicitContactSet contacts = implicit.contacts(p);
        ASSERT_EQ(contacts.contacts.size(), 1u) << "frame " << frame << ": the contact holds";
        ASSERT_TRUE(cpu::implicitVelocityUpdate(implicitParams(h), {}, model::Csr{{0, 0, 0, 0, 0}, {}},
                                                implicit.state, &contacts)
                        .converged);
        implicit.state.positions[3] += h * implicit.state.velocities[3];
        // Double rounding of an energy of about 0.1 J: 1e-12 J.
        EXPECT_LE(energy(implicit, k, thickness), before + 1e-12) << "frame " << frame;

        const cpu::ContactResult penalty = cpu::contactForces(p, explicitNode.input(), explicitNode.pairs);
        explicitNode.state.velocities[3] +=
            (h / m) * (explicitNode.state.forces[3] + penalty.forces[3]); // symplectic Euler
        explicitNode.state.positions[3] += h * explicitNode.state.velocities[3];
        explicitMax = std::max(explicitMax, energy(explicitNode, k, thickness));
    }
    EXPECT_LT(energy(implicit, k, thickness), e0);
    EXPECT_GT(explicitMax, 2.0 * e0)
        << "the explicit penalty force must gain energy here, or the test shows nothing";
}

// x·(A·y) = y·(A·x) and x·(A·x) ≥ m_min·|x|² with many contacts between two random free sheets:
// the contact blocks h²k·a aᵀ ⊗ u uᵀ are symmetric positive semidefinite.
TEST(ImplicitContactTwin, ContactBlocksKeepTheSystemSymmetricPositiveDefinite) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02), unit(-1.0, 1.0);
    cpu::NodeState state;
    std::vector<std::uint32_t> faces;
    const int n = 4; // n × n nodes per sheet, sheet 1 four millimetres above sheet 0
    for (int sheet = 0; sheet < 2; ++sheet)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                state.positions.emplace_back(0.3 * i + jitter(rng), 0.004 * sheet + 0.1 * jitter(rng),
                                             0.3 * j + jitter(rng));
                state.velocities.emplace_back(unit(rng), unit(rng), unit(rng));
                state.forces.emplace_back(0.0);
                state.inverseMasses.push_back(sheet == 0 && i == 0 ? 0.0 : 2.0 + unit(rng));
            }
    for (int sheet = 0; sheet < 2; ++sheet)
        for (int i = 0; i + 1 < n; ++i)
            for (int j = 0; j + 1 < n; ++j) {
                const auto v = [&](int a, int b) {
                    return static_cast<std::uint32_t>(sheet * n * n + a * n + b);
                };
                faces.insert(faces.end(),
                             {v(i, j), v(i, j + 1), v(i + 1, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)});
            }
    const std::vector<std::uint32_t> owned = model::ownedFeatures(faces);
    const std::vector<std::uint8_t> closed(faces.size() / 3, 0);
    std::vector<cpu::IndexPair> candidates;
    const auto faceCount = static_cast<std::uint32_t>(faces.size() / 3);
    for (std::uint32_t a = 0; a < faceCount / 2; ++a)
        for (std::uint32_t b = faceCount / 2; b < faceCount; ++b) candidates.push_back({a, b});
    const cpu::ContactInput in{&state.positions, &state.velocities, &faces,
                               &owned,           &closed,           &state.inverseMasses};
    const cpu::ImplicitContactSet contacts =
        cpu::implicitContacts(contactParams(0.01, 1e5), in, cpu::featurePairs(faces, owned, candidates));
    ASSERT_GT(contacts.contacts.size(), 20u);
    const ImplicitParams p = implicitParams(1.0 / 30.0);
    const model::Csr noSprings{std::vector<std::uint32_t>(state.positions.size() + 1, 0), {}};
    std::vector<glm::dvec3> x(state.positions.size()), y(state.positions.size());
    double minMass = std::numeric_limits<double>::infinity(), xx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        x[i] = {unit(rng), unit(rng), unit(rng)};
        y[i] = {unit(rng), unit(rng), unit(rng)};
        if (state.inverseMasses[i] > 0.0) {
            minMass = std::min(minMass, 1.0 / state.inverseMasses[i]);
            xx += glm::dot(x[i], x[i]);
        }
    }
    const auto ax = cpu::implicitSystemProduct(p, {}, noSprings, state, x, &contacts);
    const auto ay = cpu::implicitSystemProduct(p, {}, noSprings, state, y, &contacts);
    const auto without = cpu::implicitSystemProduct(p, {}, noSprings, state, x);
    double yAx = 0.0, xAy = 0.0, xAx = 0.0, xMx = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (state.inverseMasses[i] <= 0.0) continue;
        yAx += glm::dot(y[i], ax[i]);
        xAy += glm::dot(x[i], ay[i]);
        xAx += glm::dot(x[i], ax[i]);
        xMx += glm::dot(x[i], without[i]);
        scale += glm::length(x[i]) * glm::length(ay[i]) + glm::length(y[i]) * glm::length(ax[i]);
    }
    EXPECT_NEAR(yAx, xAy, 1e-13 * scale); // double rounding of the sums
    EXPECT_GT(xAx - xMx, 0.0) << "the contacts add stiffness";
    EXPECT_GE(xAx, minMass * xx);
}

// A Newton step's predicted end may have gone through a face or an edge by more than the
// thickness (decision 0024, "Crossings in the Newton steps"): with the sides from the substep's
// start (x − substep·v) the implicit solve's contact set keeps such a pair as a contact, pushed
// back to its start side with depth h_c + how far it went through; the responses' rule
// (Crossings::WithinThickness) has no contact there. A node that was already on that side at the
// start, or that passed beside the face, is no contact in either.
TEST(ImplicitContactTwin, ANewtonStepKeepsAVertexThatWentThroughAFaceAtAnyDepth) {
    const double h = 1.0 / 60.0, thickness = 0.01;
    ContactParams p = contactParams(thickness, 1.0e3);
    p.substep = h; // sides from x1 − h·v1 = x0, as the Newton step's find
    for (const double depthBelow : {0.02, 0.2})
        for (const bool closed : {false, true}) {
            // x0: 0.5·thickness above the face; x1: depthBelow under it (over its interior).
            NodeOnTriangle s(0.05, -depthBelow, (-depthBelow - 0.5 * thickness) / h);
            s.closed = {static_cast<std::uint8_t>(closed ? 1 : 0)};
            const std::vector<cpu::ContactGeometry> any =
                cpu::contactGeometries(p, s.input(), s.pairs, cpu::Crossings::AtAnyDepth);
            ASSERT_EQ(any.size(), 1u) << "closed " << closed << ", " << depthBelow << " m under";
            EXPECT_NEAR(any[0].depth, thickness + depthBelow, 1e-12);
            EXPECT_NEAR(any[0].normal.y, 1.0, 1e-12) << "back to the side it started on";
            EXPECT_EQ(cpu::implicitContacts(p, s.input(), s.pairs).contacts.size(), 1u);
            EXPECT_TRUE(cpu::contactGeometries(p, s.input(), s.pairs).empty()) << "within the thickness only";

            // Already under the face at the start: it did not go through (closed: inside).
            NodeOnTriangle under(0.05, -depthBelow, -0.1);
            under.closed = s.closed;
            EXPECT_TRUE(
                cpu::contactGeometries(p, under.input(), under.pairs, cpu::Crossings::AtAnyDepth).empty());
            // Passed the face's plane beside the face: its closest point is on an edge, no crossing.
            NodeOnTriangle beside(0.05, -depthBelow, (-depthBelow - 0.5 * thickness) / h);
            beside.closed = s.closed;
            beside.state.positions[3] = glm::dvec3(-0.3, -depthBelow, 0.5);
            EXPECT_TRUE(
                cpu::contactGeometries(p, beside.input(), beside.pairs, cpu::Crossings::AtAnyDepth).empty());
        }
    // At the substep's start (substep 0: sides from x itself) nothing has gone through.
    NodeOnTriangle now(0.05, -0.02, -1.0);
    p.substep = 0.0;
    EXPECT_TRUE(cpu::contactGeometries(p, now.input(), now.pairs, cpu::Crossings::AtAnyDepth).empty());
}

// A closed object keeps another object's vertex outside its faces (that vertex behind a face is in
// the body), but its own vertex behind its own face is not inside it: the body is thinner than the
// thickness there (a soft solid squashed flat), and pushing that vertex out would push it through
// the face, which the CCD forbids — the pair would stay deeper than the thickness for good (the
// cloth ball froze so, decision 0024, "Thin parts of closed objects"). The own vertex keeps the
// side it started on, as on an open surface.
TEST(ImplicitContactTwin, AClosedObjectsOwnVertexKeepsTheSideItStartedOn) {
    const double thickness = 0.01;
    ContactParams p = contactParams(thickness, 1.0e3);
    p.substep = 0.0; // sides from x itself
    NodeOnTriangle other(0.05, -0.5 * thickness, 0.0);
    other.closed = {1};
    const std::vector<cpu::ContactGeometry> out = cpu::contactGeometries(p, other.input(), other.pairs);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(out[0].normal.y, 1.0, 1e-12) << "another object's vertex: out through the face";
    EXPECT_NEAR(out[0].depth, 1.5 * thickness, 1e-12);

    NodeOnTriangle own = other;
    own.nodeObject = {0, 0, 0, 0};
    const std::vector<cpu::ContactGeometry> kept = cpu::contactGeometries(p, own.input(), own.pairs);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_NEAR(kept[0].normal.y, -1.0, 1e-12) << "its own vertex: kept on its side";
    EXPECT_NEAR(kept[0].depth, 0.5 * thickness, 1e-12);

    // Sides from the substep's start: above the face at x0, under it now (through it within the
    // thickness) — pushed back up, whichever object the vertex is.
    p.substep = 1.0 / 60.0;
    NodeOnTriangle through(0.05, -0.5 * thickness, -thickness * 60.0);
    through.closed = {1};
    through.nodeObject = {0, 0, 0, 0};
    const std::vector<cpu::ContactGeometry> back = cpu::contactGeometries(p, through.input(), through.pairs);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_NEAR(back[0].normal.y, 1.0, 1e-12);
    EXPECT_NEAR(back[0].depth, 1.5 * thickness, 1e-12);

    // Without the node → object map a closed face cannot be decided: an error, not a guess.
    cpu::ContactInput missing = own.input();
    missing.nodeObject = nullptr;
    EXPECT_THROW((void)cpu::contactGeometries(p, missing, own.pairs), std::invalid_argument);
}

TEST(ImplicitContactTwin, ANewtonStepKeepsEdgesThatCrossedAtAnyDistance) {
    const double h = 1.0 / 60.0, thickness = 0.01;
    ContactParams p = contactParams(thickness, 1.0e3);
    p.substep = h;
    // Edge p0p1 along x at height y1, moving down from 0.5·thickness over edge q0q1 (along z, y = 0).
    for (const double below : {0.03, 0.3}) {
        cpu::NodeState st;
        const double y1 = -below, v = (y1 - 0.5 * thickness) / h;
        st.positions = {glm::dvec3(-0.5, y1, 0.1), glm::dvec3(0.5, y1, 0.1), glm::dvec3(0.2, 0, -0.5),
                        glm::dvec3(0.2, 0, 0.5),   glm::dvec3(1, 0, 1),      glm::dvec3(-1, y1, -1)};
        st.velocities = {glm::dvec3(0, v, 0), glm::dvec3(0, v, 0), glm::dvec3(0.0),
                         glm::dvec3(0.0),     glm::dvec3(0.0),     glm::dvec3(0, v, 0)};
        st.inverseMasses = {20.0, 20.0, 0.0, 0.0, 0.0, 20.0};
        // Face 0 (0, 1, 5) owns edge 0–1; face 1 (2, 3, 4) owns edge 2–3.
        const std::vector<std::uint32_t> faces{0, 1, 5, 2, 3, 4}, owned{kOwnAll, kOwnAll};
        const std::vector<std::uint8_t> closed{0, 0};
        const cpu::ContactInput in{&st.positions, &st.velocities, &faces, &owned, &closed, &st.inverseMasses};
        const cpu::FeaturePairList pairs{{}, {{0, 3}}}; // edge 0 of face 0 against edge 0 of face 1
        const std::vector<cpu::ContactGeometry> any =
            cpu::contactGeometries(p, in, pairs, cpu::Crossings::AtAnyDepth);
        ASSERT_EQ(any.size(), 1u) << below;
        EXPECT_NEAR(any[0].depth, thickness + below, 1e-12);
        EXPECT_NEAR(any[0].normal.y, 1.0, 1e-12) << "back up: the side the edge started on";
        EXPECT_TRUE(cpu::contactGeometries(p, in, pairs).empty()) << "within the thickness only";
    }
}

} // namespace
} // namespace glcollide
