#pragma once
// C++ view of shaders/common/layout.glsl: the one declaration of the SSBO structs and bindings,
// included inside a namespace with glm aliases so the same text compiles as C++. GL-free (glm
// only), so modules below gl (model: the owned-feature bits GLC_OWN_*) use it too.

#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace glcollide::gpu {

using uint = std::uint32_t;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;

#include "../../shaders/common/layout.glsl"

// std430: structs of 4-byte scalars have 4-byte alignment; we keep every struct a multiple of
// 16 bytes so arrays of them can be bound with glBindBufferRange at 16-byte-aligned offsets.
static_assert(sizeof(vec4) == 16);
static_assert(sizeof(GpuSpring) == 32);
static_assert(offsetof(GpuSpring, nodeA) == 0);
static_assert(offsetof(GpuSpring, nodeB) == 4);
static_assert(offsetof(GpuSpring, restLength) == 8);
static_assert(offsetof(GpuSpring, stiffness) == 12);
static_assert(offsetof(GpuSpring, damping) == 16);
static_assert(offsetof(GpuSpring, object) == 20);
static_assert(sizeof(GpuObject) == 32);
static_assert(offsetof(GpuObject, firstNode) == 0);
static_assert(offsetof(GpuObject, nodeCount) == 4);
static_assert(offsetof(GpuObject, firstFace) == 8);
static_assert(offsetof(GpuObject, faceCount) == 12);
static_assert(offsetof(GpuObject, firstSpring) == 16);
static_assert(offsetof(GpuObject, springCount) == 20);
static_assert(offsetof(GpuObject, firstBox) == 24);
static_assert(offsetof(GpuObject, closed) == 28);
static_assert(sizeof(GpuSolverState) == 32);
static_assert(offsetof(GpuSolverState, doneAt) == 12);
static_assert(offsetof(GpuSolverState, maxIterations) == 16);
static_assert(sizeof(GpuBox) == 32);
static_assert(offsetof(GpuBox, lo) == 0);
static_assert(offsetof(GpuBox, hi) == 16);
static_assert(sizeof(GpuImplicitContact) == 48);
static_assert(offsetof(GpuImplicitContact, weights) == 16);
static_assert(offsetof(GpuImplicitContact, normalForce) == 32);
static_assert(sizeof(GpuFaceInfo) == 16);
static_assert(offsetof(GpuFaceInfo, object) == 0);
static_assert(offsetof(GpuFaceInfo, box) == 4);
static_assert(offsetof(GpuFaceInfo, owned) == 8);
static_assert(sizeof(GpuListCounter) == 8);
static_assert(offsetof(GpuListCounter, count) == 0);
static_assert(offsetof(GpuListCounter, capacity) == 4);
static_assert(sizeof(GpuCollisionCounters) == 8 * GLC_LIST_COUNT + 4 * GLC_STAT_COUNT);
static_assert(offsetof(GpuCollisionCounters, lists) == 0);
static_assert(offsetof(GpuCollisionCounters, stats) == 8 * GLC_LIST_COUNT);
static_assert(offsetof(GpuEnergyGuard, partials) == 64);
static_assert(sizeof(GpuEnergyGuard) == 64 + 16 * GLC_ENERGY_GROUPS + 32 * GLC_ENERGY_GROUPS);
static_assert(offsetof(GpuLineSearch, partials) == 16);
static_assert(sizeof(GpuLineSearch) == 16 + 16 * GLC_ENERGY_GROUPS + 32 * GLC_ENERGY_GROUPS);
static_assert(sizeof(GpuHealth) == 16);
static_assert(offsetof(GpuHealth, firstBadNode) == 0);
static_assert(offsetof(GpuHealth, badSubstep) == 4);
static_assert(GLC_RADIAL_CELL_GRID % 4 == 0 &&
              GLC_RADIAL_COARSE_GRID % 4 == 0); // 4 cells consecutive in x per word
static_assert(GLC_RADIAL_FOOT_BINS == 8);       // a byte per cell
static_assert(GLC_RADIAL_COARSE_WORDS == GLC_RADIAL_COARSE_GRID * GLC_RADIAL_COARSE_GRID *
                                             GLC_RADIAL_COARSE_GRID * GLC_RADIAL_FOOT_BINS / 32);
static_assert(GLC_RADIAL_CELL_WORDS == GLC_RADIAL_COARSE_WORDS + GLC_RADIAL_CELL_GRID * GLC_RADIAL_CELL_GRID *
                                                                     GLC_RADIAL_CELL_GRID *
                                                                     GLC_RADIAL_FOOT_BINS / 32);

} // namespace glcollide::gpu
