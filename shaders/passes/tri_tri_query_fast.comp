#version 430 core
// TriTriQuery, fast precision — answers a batch of independent triangle-triangle queries
// (glcollide query tritri, tests, benchmarks). One invocation per pair: reads 18 floats
// (a0 a1 a2 b0 b1 b2, xyz each) and writes 1 when triTriIntersect of common/tri_tri.glsl
// (Moeller 1997) says the closed triangles intersect, else 0. CPU twin: cpu::fastTrianglesIntersect.
#include "common/layout.glsl"
#include "common/tri_tri.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_QUERY_TRIANGLES) readonly buffer QueryTrianglesBuf { float g_queryTriangles[]; };
layout(std430, binding = GLC_BIND_QUERY_RESULTS) writeonly buffer QueryResultsBuf { uint g_queryResults[]; };

uniform uint u_pairCount;

vec3 corner(uint base, uint k) {
    uint o = base + 3u * k;
    return vec3(g_queryTriangles[o], g_queryTriangles[o + 1u], g_queryTriangles[o + 2u]);
}

void main() {
    uint i = globalIndex();
    if (i >= u_pairCount) return;
    uint base = 18u * i;
    g_queryResults[i] = triTriIntersect(corner(base, 0u), corner(base, 1u), corner(base, 2u),
                                        corner(base, 3u), corner(base, 4u), corner(base, 5u)) ? 1u : 0u;
}
