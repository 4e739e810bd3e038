// Helpers shared by the collision passes (BBUpdate, BBCollision, TriTri; seeds/002 Alg. 1-3).
// The CPU twin (src/cpu/collision_twin.cpp) repeats each of them in the same float arithmetic, so
// boxes and candidate pairs match bit for bit (docs/broad-phase.md).

// Bits of u_pairRules: which face pairs may collide.
#define GLC_RULE_BETWEEN_OBJECTS 1u // faces of different objects (effect `collisions`)
#define GLC_RULE_SELF 2u            // faces of one object that share no node (effect `self_collisions`)

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

// Appends to a counted list: the count stays exact even when the list is full, so the host can
// grow the list and rerun (DESIGN.md "Append buffers never drop data").
#define GLC_APPEND(counter, capacity, list, item) { uint slot_ = atomicAdd(counter, 1u); if (slot_ < capacity) list[slot_] = item; }
