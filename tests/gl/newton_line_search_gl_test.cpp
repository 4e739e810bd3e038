// The Newton steps' line search (NewtonLineSearchPass, shaders/passes/newton_line_search.comp;
// decision 0024, "Line search") against its double-precision twin cpu::incrementalPotential on
// random spring networks with gravity, air damping and the ground's penalty.
//
// What is checked, for each seed: the GPU's Φ at v1 + α·δ (α = 0, ¼, ½, 1) equals the twin's within
// the GPU sum's stated resolution (NewtonLineSearchPass::resolution × the terms' magnitude scale:
// (chain + 8)·2⁻²⁴·S, Higham §4.2, the same bound as the energy guard's; the candidate's float v
// and x are two of the 8 roundings per term it allows); the pass keeps the fraction the twin's
// values choose (the first α whose Φ is not above Φ(v1) by more than the resolution, else 0),
// wherever the twin's margin from that threshold exceeds both sums' tolerances (closer cases could
// go either way on any device and are counted, not judged); and the velocities and predicted
// positions it leaves are that candidate's. The steps run along the twin's steepest descent at
// multiples of the distance to the minimum on that line, so that full steps, steps shortened to ½
// and ¼ and rejected steps all occur (asserted: a test set that never shortens would prove nothing
// about the search; llvmpipe: 12 / 12 / 12 of 36, none too close to call).

#include "cpu/dynamics_twin.hpp"
#include "passes/newton_line_search.hpp"
#include "support/random_dynamics_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace glcollide {
namespace {

using testing_support::download;
using testing_support::makeRandomModel;
using testing_support::pack;
using testing_support::toFloat;
using testing_support::upload;
using testing_support::uploadModel;

constexpr double kH = 1.0 / 60.0;

passes::LineSearchParams searchParams() {
    passes::LineSearchParams p;
    p.potentials.gravity = glm::dvec3(0.0, -9.81, 0.0);
    p.airDamping = 0.5;
    p.potentials.springs = true;
    p.potentials.contacts = false;
    p.potentials.groundStiffness = 1000.0;
    p.potentials.groundLevel = -0.25;
    return p;
}

cpu::PotentialParams twinParams(const passes::LineSearchParams& p) {
    cpu::PotentialParams t;
    t.h = toFloat(kH);
    t.airDamping = toFloat(p.airDamping);
    t.gravity = glm::dvec3(glm::vec3(p.potentials.gravity));
    t.groundStiffness = toFloat(p.potentials.groundStiffness);
    t.groundLevel = toFloat(p.potentials.groundLevel);
    return t;
}

std::vector<glm::dvec3> toFloats(std::vector<glm::dvec3> v) {
    for (glm::dvec3& x : v) x = glm::dvec3(glm::vec3(x));
    return v;
}

std::vector<glm::dvec3> candidate(const std::vector<glm::dvec3>& start, const std::vector<glm::dvec3>& full,
                                  double alpha) {
    std::vector<glm::dvec3> v(start.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = start[i] + alpha * (full[i] - start[i]);
    return v;
}

TEST(NewtonLineSearchGl, KeepsTheFractionTheTwinsPotentialChooses) {
    const passes::LineSearchParams params = searchParams();
    const cpu::PotentialParams twin = twinParams(params);
    // Steps along the twin's steepest descent, as multiples k of the distance t* to its minimum
    // along that line (Φ locally quadratic: k < 2 lowers Φ, 2 < k < 4 needs ½, 4 < k < 8 needs ¼,
    // above 8 or k < 0 nothing lowers it).
    constexpr std::array<double, 6> kMultiples = {0.5, 1.5, 3.0, 6.0, 12.0, -1.0};
    int full = 0, shortened = 0, rejected = 0, undecided = 0, decided = 0;
    for (std::uint32_t seed = 1; seed <= 36; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const testing_support::RandomModel model = makeRandomModel(48, seed);
        const std::size_t n = model.state.positions.size();
        std::mt19937 rng(1000 + seed);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
        const std::vector<double>& w = model.state.inverseMasses;
        // v0 the substep's start, v1 the Newton step's start near it.
        const std::vector<glm::dvec3> v0 = model.state.velocities;
        std::vector<glm::dvec3> v1(n), vFull(n);
        for (std::size_t i = 0; i < n; ++i)
            v1[i] = w[i] > 0.0 ? v0[i] + 0.1 * glm::dvec3(unit(rng), unit(rng), unit(rng)) : v0[i];
        v1 = toFloats(v1);
        auto phiAt = [&](const std::vector<glm::dvec3>& v) {
            return cpu::incrementalPotential(twin, model.state.positions, v0, v, w, &model.springs).total;
        };
        // The twin's gradient by central differences, then the curvature along it.
        std::vector<glm::dvec3> descent(n, glm::dvec3(0.0));
        double norm2 = 0.0;
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3 && w[i] > 0.0; ++c) {
                std::vector<glm::dvec3> plus = v1, minus = v1;
                plus[i][c] += 1e-5;
                minus[i][c] -= 1e-5;
                descent[i][c] = -(phiAt(plus) - phiAt(minus)) / 2e-5;
                norm2 += descent[i][c] * descent[i][c];
            }
        const double norm = std::sqrt(norm2);
        for (glm::dvec3& d : descent) d /= norm;
        std::vector<glm::dvec3> tip(n);
        for (std::size_t i = 0; i < n; ++i) tip[i] = v1[i] + descent[i];
        const double probe = 1e-2;
        const double curvature =
            (phiAt(candidate(v1, tip, probe)) - 2.0 * phiAt(v1) + phiAt(candidate(v1, tip, -probe))) /
            (probe * probe);
        ASSERT_GT(curvature, 0.0);
        const double distance = kMultiples[seed % kMultiples.size()] * norm / curvature;
        for (std::size_t i = 0; i < n; ++i) vFull[i] = v1[i] + distance * descent[i];
        vFull = toFloats(vFull);

        passes::DeviceBuffers b = uploadModel(model);
        b.velocities = upload("velocities", pack(vFull)); // the Newton step's solve left v1 + δ
        b.predictedPositions = upload("predictedPositions", pack(model.state.positions, &w));
        const gl::Buffer start = upload("v0", pack(v0)), stepStart = upload("v1", pack(v1));
        const passes::NewtonLineSearchPass pass(params, b.nodeCount, b.springCount);
        const passes::LineSearchStep step = pass.dispatch(b, nullptr, start, stepStart, kH);
        const float kept = step.fraction;
        const double resolution = pass.resolution();
        // How far the kept step moved x1: α·h·max|δ| over the free nodes, δ = vFull − v1 (both
        // floats, so δ's entries are exact in double). The GPU's |δ| is a float length: the
        // subtraction, squares, sum and square root round it by at most 6 units in the last place
        // of |vFull| + |v1| (Higham §3.1, with the inputs' sizes bounding the difference's error).
        double largestChange = 0.0, changeTol = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            if (w[i] <= 0.0) continue;
            largestChange = std::max(largestChange, glm::length(vFull[i] - v1[i]));
            changeTol = std::max(changeTol, 6.0 * testing_support::kUnitRoundoff *
                                                (glm::length(vFull[i]) + glm::length(v1[i])));
        }
        EXPECT_NEAR(step.largestMove, kept * kH * largestChange, kept * kH * changeTol) << "seed " << seed;
        // What it left: the kept candidate and its positions.
        const std::vector<glm::dvec3> keptV = candidate(v1, vFull, kept);
        const std::vector<glm::dvec4> gpuV = download(b.velocities, b.nodeCount);
        const std::vector<glm::dvec4> gpuX = download(b.predictedPositions, b.nodeCount);
        for (std::size_t i = 0; i < n; ++i) {
            if (w[i] <= 0.0) continue;
            // One float rounding of v1 + α·δ (α a power of two) and of x0 + h·v.
            const double vTol = 4.0 * testing_support::kUnitRoundoff *
                                (glm::length(v1[i]) + glm::length(vFull[i]) + glm::length(keptV[i]));
            EXPECT_LE(glm::length(glm::dvec3(gpuV[i]) - keptV[i]), vTol) << "node " << i;
            const glm::dvec3 x = model.state.positions[i] + kH * keptV[i];
            EXPECT_LE(glm::length(glm::dvec3(gpuX[i]) - x),
                      kH * vTol + 4.0 * testing_support::kUnitRoundoff * glm::length(x))
                << "node " << i;
        }

        // Φ at each candidate, GPU against twin; then the twin's choice.
        struct Value {
            double twin, gpu, magnitude;
        };
        auto value = [&](double alpha) {
            const cpu::Potential t = cpu::incrementalPotential(
                twin, model.state.positions, v0, candidate(v1, vFull, alpha), w, &model.springs);
            const passes::PotentialSum g = pass.evaluate(b, nullptr, static_cast<float>(alpha), kH);
            EXPECT_NEAR(g.total, t.total, resolution * t.magnitude) << "alpha " << alpha;
            return Value{t.total, g.total, t.magnitude};
        };
        const Value atStart = value(0.0);
        double expected = 0.0;
        bool ambiguous = false;
        for (const float alpha : passes::NewtonLineSearchPass::kFractions) {
            const Value at = value(alpha);
            const double margin =
                atStart.twin + resolution * (atStart.magnitude + at.magnitude) - at.twin; // ≥ 0: accepted
            if (std::abs(margin) <= 2.0 * resolution * (atStart.magnitude + at.magnitude)) ambiguous = true;
            if (margin >= 0.0) {
                expected = alpha;
                break;
            }
        }
        if (ambiguous) {
            ++undecided;
            continue;
        }
        ++decided;
        EXPECT_EQ(kept, static_cast<float>(expected));
        if (kept == 1.0f)
            ++full;
        else if (kept > 0.0f)
            ++shortened;
        else
            ++rejected;
    }
    // Every branch ran on decided cases, and few cases were too close to call.
    EXPECT_GT(full, 0);
    EXPECT_GT(shortened, 0);
    EXPECT_GT(rejected, 0);
    EXPECT_GE(decided, 30) << undecided << " undecided";
}

} // namespace
} // namespace glcollide
