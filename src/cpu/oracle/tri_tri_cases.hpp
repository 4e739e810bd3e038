#pragma once
// Triangle-pair generators shared by the narrow-phase tests and the tri-tri benchmark: the hard
// cases (hand-made, touching / coplanar / one ulp apart / tiny / far / zero-area / denormal /
// huge) and seeded random sets, uniform and near-degenerate. All coordinates are floats, the
// precision the GPU works in; the oracle gets them widened to double exactly.
//
// Where things live: src/model/ holds the model the GPU and the twins share (no GL, no GMP);
// src/cpu/ the CPU twins of the GPU passes; src/cpu/oracle/ (here) the references they and the GPU
// are judged by: exact_tri_tri (GMP), ground_truth (exact intersecting pairs of a scene, deepest
// penetration) and tri_tri_cases (the triangle pairs, with the oracle on a float pair).

#include "cpu/oracle/exact_tri_tri.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::cpu {

/// a0 a1 a2 b0 b1 b2, xyz each.
using FloatTriPair = std::array<float, 18>;

/// A hard case's answer derived by hand from its construction, independently of the oracle.
enum class HandAnswer : std::uint8_t {
    Missing,   ///< none recorded: the tests fail on such a case
    Disjoint,  ///< the closed triangles share no point
    Intersect, ///< they share at least one point (touching counts)
};

struct NamedTriPair {
    std::string name;
    FloatTriPair pair;
    HandAnswer expected = HandAnswer::Missing; ///< hard cases: the hand-derived answer
    std::string reason = {};                   ///< hard cases: one line saying why, from the construction
};

/// The hand-made hard cases, each in its six variants (three corner rotations, both orders), each
/// with its hand-derived answer and reason (the same for all six variants).
std::vector<NamedTriPair> hardTriTriCases();

/// Seeded random sets.
enum class TriTriSet {
    Uniform,    ///< corners uniform in a cube: mostly clear-cut, about 10 % intersecting
    Grid,       ///< corners on a coarse integer grid: exact coplanarity, touching, zero area
    Coplanar,   ///< both triangles in one slanted plane (exactly, on a lattice of the plane)
    Touching,   ///< pairs built to touch: shared corner, shared edge, corner on face, edge on edge
    Ulp,        ///< touching pairs with one coordinate moved one float step
    Degenerate, ///< zero-area triangles (segments, points) against triangles and each other
    Scaled,     ///< grid pairs scaled to 1e-6 .. 1e6 and moved far from the origin
};

inline constexpr std::array<TriTriSet, 7> kAllTriTriSets = {
    TriTriSet::Uniform, TriTriSet::Grid,       TriTriSet::Coplanar, TriTriSet::Touching,
    TriTriSet::Ulp,     TriTriSet::Degenerate, TriTriSet::Scaled};

const char* toString(TriTriSet set);

/// `count` pairs of the set, deterministic for a given seed.
std::vector<FloatTriPair> randomTriTriPairs(TriTriSet set, std::size_t count, std::uint32_t seed);

/// Corner k (0..5) of a pair as doubles (exact).
glm::dvec3 corner(const FloatTriPair& pair, int k);

/// The oracle on a float pair.
bool exactPairIntersects(const FloatTriPair& pair);

} // namespace glcollide::cpu
