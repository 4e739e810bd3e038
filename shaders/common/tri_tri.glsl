// Triangle-triangle intersection, the narrow phase of the collision pipeline (TriTri in the
// AABB-octree paper, seeds/002 Alg. 3). Semantics (docs/collisions.md): closed triangles, so
// touching counts; coplanar pairs are decided in their plane; a zero-area triangle is the segment
// or point it covers. Two precisions, chosen at compile time:
//   GLC_PRECISION_ROBUST  float filter with a certified error bound, exact fallback: always
//                         the answer of the rational oracle src/cpu/exact_tri_tri.
//   (default)             fast: float arithmetic with epsilons.
//
// Contract used by the collision passes:
//   bool triTriIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2);
// (PLACEHOLDER until the narrow phase lands: separating-axis test on the two face normals only.)

bool triTriIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    vec3 n = cross(a1 - a0, a2 - a0);
    float d0 = dot(n, b0 - a0), d1 = dot(n, b1 - a0), d2 = dot(n, b2 - a0);
    if ((d0 > 0.0 && d1 > 0.0 && d2 > 0.0) || (d0 < 0.0 && d1 < 0.0 && d2 < 0.0)) return false;
    vec3 m = cross(b1 - b0, b2 - b0);
    float e0 = dot(m, a0 - b0), e1 = dot(m, a1 - b0), e2 = dot(m, a2 - b0);
    return !((e0 > 0.0 && e1 > 0.0 && e2 > 0.0) || (e0 < 0.0 && e1 < 0.0 && e2 < 0.0));
}
