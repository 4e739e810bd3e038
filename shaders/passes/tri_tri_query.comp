#version 430 core
// TriTriQuery — answers a batch of independent triangle-triangle queries (glcollide query
// tritri, tests, benchmarks) with the narrow-phase test of shaders/common/tri_tri.glsl
// (Moeller 1997 when fast; exact-predicate robust mode with GLC_PRECISION_ROBUST, Shewchuk 1997).
// One invocation per pair: reads 18 floats (a0 a1 a2 b0 b1 b2, xyz each), writes 1 when the closed
// triangles intersect, else 0, and adds the number of predicates that fell back to the exact path
// to the stats counter. CPU references: cpu::exactTrianglesIntersect (robust), cpu::fastTrianglesIntersect (fast).
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_QUERY_TRIANGLES) readonly buffer QueryTrianglesBuf { float g_queryTriangles[]; };
layout(std430, binding = GLC_BIND_QUERY_RESULTS) writeonly buffer QueryResultsBuf { uint g_queryResults[]; };
layout(std430, binding = GLC_BIND_QUERY_STATS) buffer QueryStatsBuf { uint g_queryStats[]; };

uniform uint u_pairCount;

uint g_exactFallbacks = 0u; // this invocation's count, added to the buffer once at the end
#define GLC_COUNT_EXACT_FALLBACK() (++g_exactFallbacks)
#include "common/tri_tri.glsl"

vec3 corner(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_queryTriangles[o], g_queryTriangles[o + 1u], g_queryTriangles[o + 2u]);
}

void main() {
    uint i = globalIndex();
    if (i >= u_pairCount) return;
    uint base = 18u * i;
    bool hit = triTriIntersect(corner(base, 0u), corner(base, 1u), corner(base, 2u), corner(base, 3u),
                               corner(base, 4u), corner(base, 5u));
    g_queryResults[i] = hit ? 1u : 0u;
    if (g_exactFallbacks != 0u) atomicAdd(g_queryStats[0], g_exactFallbacks);
}
