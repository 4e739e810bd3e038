// Helpers shared by the collision passes (BBUpdate, BBCollision, TriTri; seeds/002 Alg. 1-3).
// The CPU twin (src/cpu/collision_twin.cpp) repeats each of them in the same float arithmetic, so
// boxes and candidate pairs match bit for bit (docs/broad-phase.md).

// u_pairRules holds GLC_RULE_* bits (layout.glsl): which face pairs may collide.

// Closed AABB overlap: lo_a <= hi_b and lo_b <= hi_a on every axis. An empty box (lo > hi)
// overlaps nothing that is finite.
bool boxesOverlap(vec3 loA, vec3 hiA, vec3 loB, vec3 hiB) {
    return all(lessThanEqual(loA, hiB)) && all(lessThanEqual(loB, hiA));
}

bool facesShareNode(uvec3 a, uvec3 b) {
    return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// Whether objects (a, b) may collide at all under `rules` (i.e. some pair of their faces may).
bool objectsMayCollide(uint objectA, uint objectB, uint rules) {
    return objectA == objectB ? (rules & GLC_RULE_SELF) != 0u : (rules & GLC_RULE_BETWEEN_OBJECTS) != 0u;
}

// The valid-pair rule for two different faces.
bool validFacePair(uint objectA, uvec3 nodesA, uint objectB, uvec3 nodesB, uint rules) {
    if (objectA != objectB) return (rules & GLC_RULE_BETWEEN_OBJECTS) != 0u;
    return (rules & GLC_RULE_SELF) != 0u && !facesShareNode(nodesA, nodesB);
}

// Face box: the AABB of the three float vertices, inflated by the half thickness in float.
void faceBox(vec3 p0, vec3 p1, vec3 p2, float halfThickness, out vec3 lo, out vec3 hi) {
    lo = min(min(p0, p1), p2) - vec3(halfThickness);
    hi = max(max(p0, p1), p2) + vec3(halfThickness);
}
