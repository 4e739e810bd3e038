#version 430 core
// TriTriQuery — answers a batch of independent triangle-triangle queries (glcollide query
// tritri, tests, benchmarks, the robust self-check). One invocation per pair: reads 18 floats
// (a0 a1 a2 b0 b1 b2, xyz each) and writes 1 when the closed triangles intersect, else 0.
//   fast (default)        triTriIntersect of common/tri_tri.glsl (Moeller 1997).
//   GLC_PRECISION_ROBUST  glcTriTriFiltered of common/tri_tri_robust.glsl; a pair the filters
//                         cannot decide is appended to the undecided list (count in stats[1]),
//                         which tri_tri_query_exact.comp finishes exactly.
// CPU references: cpu::exactTrianglesIntersect (the oracle), cpu::fastTrianglesIntersect (fast's
// twin), shader::robustTrianglesIntersect (this code compiled as C++).
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_QUERY_TRIANGLES) readonly buffer QueryTrianglesBuf { float g_queryTriangles[]; };
layout(std430, binding = GLC_BIND_QUERY_RESULTS) writeonly buffer QueryResultsBuf { uint g_queryResults[]; };

uniform uint u_pairCount;

#ifdef GLC_PRECISION_ROBUST
#include "common/tri_tri_robust.glsl"
// stats[0]: predicates evaluated exactly (the exact pass), stats[1]: undecided pairs.
layout(std430, binding = GLC_BIND_QUERY_STATS) buffer QueryStatsBuf { uint g_queryStats[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) writeonly buffer UndecidedBuf { uint g_undecided[]; };
#else
#include "common/tri_tri.glsl"
#endif

vec3 corner(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_queryTriangles[o], g_queryTriangles[o + 1u], g_queryTriangles[o + 2u]);
}

void main() {
    uint i = globalIndex();
    if (i >= u_pairCount) return;
    uint base = 18u * i;
    vec3 a0 = corner(base, 0u), a1 = corner(base, 1u), a2 = corner(base, 2u);
    vec3 b0 = corner(base, 3u), b1 = corner(base, 4u), b2 = corner(base, 5u);
#ifdef GLC_PRECISION_ROBUST
    int answer = glcTriTriFiltered(a0, a1, a2, b0, b1, b2);
    if (answer == GLC_UNDECIDED) {
        g_undecided[atomicAdd(g_queryStats[1], 1u)] = i; // capacity: one per pair
        return;
    }
    g_queryResults[i] = uint(answer);
#else
    g_queryResults[i] = triTriIntersect(a0, a1, a2, b0, b1, b2) ? 1u : 0u;
#endif
}
