// Fast triangle-triangle intersection, the narrow phase's `fast` precision (TriTri in the
// AABB-octree paper, seeds/002 Alg. 3): Moeller 1997, "A Fast Triangle-Triangle Intersection
// Test" (NoDivTriTriIsect), float arithmetic, |plane distance| < 1e-6 counts as coplanar. CPU twin:
// src/cpu/fast_tri_tri.cpp. The `robust` precision is common/tri_tri_robust.glsl. Design and
// measured disagreements of both: docs/narrow-phase.md.
//
// Semantics: closed triangles, so touching at a vertex or along an edge counts (up to the epsilon).
//   bool triTriIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2);

#ifndef GLC_TRI_TRI_GLSL
#define GLC_TRI_TRI_GLSL

// ---------------------------------------------------------------------------------------------
// Moeller 1997, NoDivTriTriIsect, transcribed operation for operation (the CPU twin in
// src/cpu/fast_tri_tri.cpp follows the same order). GLC_FAST_EPSILON is the paper's EPSILON:
// an absolute threshold on the unnormalised plane distances N.x + d (units: length^3).
// `precise` (no FMA contraction) and the written-out dot product make the answers reproducible:
// every conforming device computes the same floats as the twin (denormal flushing aside), so
// fast's disagreements with the oracle measured once hold everywhere. On llvmpipe, without them,
// the GPU differed from the twin on 0.8-1.9 % of the one-ulp and scaled sets (docs/narrow-phase.md).

const float GLC_FAST_EPSILON = 0.000001;

// Coplanar triangles: edge-edge crossings and corner containment in the axis-aligned plane where
// the projected area of N is largest (Moeller 1997, coplanar_tri_tri).
bool glcFastEdgeEdge(vec2 v0, vec2 a, vec2 u0, vec2 u1) {
    precise float bx = u0.x - u1.x, by = u0.y - u1.y;
    precise float cx = v0.x - u0.x, cy = v0.y - u0.y;
    precise float f = a.y * bx - a.x * by;
    precise float d = by * cx - bx * cy;
    if ((f > 0.0 && d >= 0.0 && d <= f) || (f < 0.0 && d <= 0.0 && d >= f)) {
        precise float e = a.x * cy - a.y * cx;
        if (f > 0.0) {
            if (e >= 0.0 && e <= f) return true;
        } else {
            if (e <= 0.0 && e >= f) return true;
        }
    }
    return false;
}

bool glcFastEdgeAgainstTriEdges(vec2 v0, vec2 v1, vec2 u0, vec2 u1, vec2 u2) {
    precise vec2 a = v1 - v0;
    return glcFastEdgeEdge(v0, a, u0, u1) || glcFastEdgeEdge(v0, a, u1, u2) || glcFastEdgeEdge(v0, a, u2, u0);
}

bool glcFastPointInTri(vec2 v0, vec2 u0, vec2 u1, vec2 u2) {
    precise float a = u1.y - u0.y, b = -(u1.x - u0.x), c = -a * u0.x - b * u0.y;
    precise float d0 = a * v0.x + b * v0.y + c;
    a = u2.y - u1.y;
    b = -(u2.x - u1.x);
    c = -a * u1.x - b * u1.y;
    precise float d1 = a * v0.x + b * v0.y + c;
    a = u0.y - u2.y;
    b = -(u0.x - u2.x);
    c = -a * u2.x - b * u2.y;
    precise float d2 = a * v0.x + b * v0.y + c;
    return d0 * d1 > 0.0 && d0 * d2 > 0.0;
}

bool glcFastCoplanar(vec3 n, vec3 v0, vec3 v1, vec3 v2, vec3 u0, vec3 u1, vec3 u2) {
    vec3 a = abs(n);
    int i0, i1;
    if (a.x > a.y) {
        if (a.x > a.z) { i0 = 1; i1 = 2; } else { i0 = 0; i1 = 1; }
    } else {
        if (a.z > a.y) { i0 = 0; i1 = 1; } else { i0 = 0; i1 = 2; }
    }
    precise vec2 pv0 = vec2(v0[i0], v0[i1]), pv1 = vec2(v1[i0], v1[i1]), pv2 = vec2(v2[i0], v2[i1]);
    precise vec2 pu0 = vec2(u0[i0], u0[i1]), pu1 = vec2(u1[i0], u1[i1]), pu2 = vec2(u2[i0], u2[i1]);
    if (glcFastEdgeAgainstTriEdges(pv0, pv1, pu0, pu1, pu2)) return true;
    if (glcFastEdgeAgainstTriEdges(pv1, pv2, pu0, pu1, pu2)) return true;
    if (glcFastEdgeAgainstTriEdges(pv2, pv0, pu0, pu1, pu2)) return true;
    return glcFastPointInTri(pv0, pu0, pu1, pu2) || glcFastPointInTri(pu0, pv0, pv1, pv2);
}

// NEWCOMPUTE_INTERVALS: the projection interval of one triangle on the intersection line, as
// (a, b, c, x0, x1). Returns false when both triangles are coplanar.
bool glcFastInterval(float vv0, float vv1, float vv2, float d0, float d1, float d2, float d0d1, float d0d2,
                     out float a, out float b, out float c, out float x0, out float x1) {
    a = 0.0; b = 0.0; c = 0.0; x0 = 0.0; x1 = 0.0;
    if (d0d1 > 0.0) {
        a = vv2; b = (vv0 - vv2) * d2; c = (vv1 - vv2) * d2; x0 = d2 - d0; x1 = d2 - d1;
    } else if (d0d2 > 0.0) {
        a = vv1; b = (vv0 - vv1) * d1; c = (vv2 - vv1) * d1; x0 = d1 - d0; x1 = d1 - d2;
    } else if (d1 * d2 > 0.0 || d0 != 0.0) {
        a = vv0; b = (vv1 - vv0) * d0; c = (vv2 - vv0) * d0; x0 = d0 - d1; x1 = d0 - d2;
    } else if (d1 != 0.0) {
        a = vv1; b = (vv0 - vv1) * d1; c = (vv2 - vv1) * d1; x0 = d1 - d0; x1 = d1 - d2;
    } else if (d2 != 0.0) {
        a = vv2; b = (vv0 - vv2) * d2; c = (vv1 - vv2) * d2; x0 = d2 - d0; x1 = d2 - d1;
    } else {
        return false;
    }
    return true;
}

// dot() may sum in any order; Moeller's DOT is ((x + y) + z).
float glcFastDot(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

bool triTriIntersect(vec3 v0, vec3 v1, vec3 v2, vec3 u0, vec3 u1, vec3 u2) {
    precise vec3 e1 = v1 - v0, e2 = v2 - v0;
    precise vec3 n1 = cross(e1, e2);
    precise float d1 = -glcFastDot(n1, v0);
    precise float du0 = glcFastDot(n1, u0) + d1, du1 = glcFastDot(n1, u1) + d1, du2 = glcFastDot(n1, u2) + d1;
    if (abs(du0) < GLC_FAST_EPSILON) du0 = 0.0;
    if (abs(du1) < GLC_FAST_EPSILON) du1 = 0.0;
    if (abs(du2) < GLC_FAST_EPSILON) du2 = 0.0;
    precise float du0du1 = du0 * du1, du0du2 = du0 * du2;
    if (du0du1 > 0.0 && du0du2 > 0.0) return false;

    e1 = u1 - u0;
    e2 = u2 - u0;
    precise vec3 n2 = cross(e1, e2);
    precise float d2 = -glcFastDot(n2, u0);
    precise float dv0 = glcFastDot(n2, v0) + d2, dv1 = glcFastDot(n2, v1) + d2, dv2 = glcFastDot(n2, v2) + d2;
    if (abs(dv0) < GLC_FAST_EPSILON) dv0 = 0.0;
    if (abs(dv1) < GLC_FAST_EPSILON) dv1 = 0.0;
    if (abs(dv2) < GLC_FAST_EPSILON) dv2 = 0.0;
    precise float dv0dv1 = dv0 * dv1, dv0dv2 = dv0 * dv2;
    if (dv0dv1 > 0.0 && dv0dv2 > 0.0) return false;

    precise vec3 dir = cross(n1, n2);
    precise float mx = abs(dir.x);
    int index = 0;
    precise float bb = abs(dir.y), cc = abs(dir.z);
    if (bb > mx) { mx = bb; index = 1; }
    if (cc > mx) { mx = cc; index = 2; }
    precise float vp0 = v0[index], vp1 = v1[index], vp2 = v2[index];
    precise float up0 = u0[index], up1 = u1[index], up2 = u2[index];

    precise float a, b, c, x0, x1;
    if (!glcFastInterval(vp0, vp1, vp2, dv0, dv1, dv2, dv0dv1, dv0dv2, a, b, c, x0, x1))
        return glcFastCoplanar(n1, v0, v1, v2, u0, u1, u2);
    precise float d, e, f, y0, y1;
    if (!glcFastInterval(up0, up1, up2, du0, du1, du2, du0du1, du0du2, d, e, f, y0, y1))
        return glcFastCoplanar(n1, v0, v1, v2, u0, u1, u2);

    precise float xx = x0 * x1, yy = y0 * y1, xxyy = xx * yy;
    precise float tmp = a * xxyy;
    precise vec2 isect1 = vec2(tmp + b * x1 * yy, tmp + c * x0 * yy);
    tmp = d * xxyy;
    precise vec2 isect2 = vec2(tmp + e * xx * y1, tmp + f * xx * y0);
    if (isect1.x > isect1.y) isect1 = isect1.yx;
    if (isect2.x > isect2.y) isect2 = isect2.yx;
    return !(isect1.y < isect2.x || isect2.y < isect1.x);
}

#endif // GLC_TRI_TRI_GLSL
