#version 430 core
// ContactResponse — penalty forces for proximity contacts on the candidate face pairs of the
// broad phase (the response stage of the AABB-octree pipeline, seeds/002 Fig. 4; the model is
// the thickness-based penalty of cloth/deformable contact codes, docs/collisions.md):
//  * vertex-face: each vertex owned by one face of a pair against the other face; within the
//    thickness h it is pushed away from its closest point on the face. For a face of a closed
//    object (outward normals) a vertex whose projection lies inside the face and that is at most
//    h below it is pushed out along the normal, so a shallow penetration is undone, not deepened.
//    A vertex near an edge or a vertex of the other mesh is near every face around that feature:
//    the contact counts only for the face that owns the closest feature (GLC_OWN_* bits), and a
//    vertex-vertex contact only from its lower node, so a vertex meeting a vertex of valence 6
//    gets one contact, not twelve (the stiffness the substep
//    rule assumes; six gave the soak scene's energy gain, docs/collisions.md).
//  * edge-edge: each edge owned by one face against each owned edge of the other, pushed apart
//    along the line of their closest points when closer than h, when both closest points are
//    inside their edges (an endpoint is a vertex: the vertex-face contacts have it; crossing
//    edges, distance 0, have no direction and are left to the vertex-face contacts too).
// Force per contact: clamp(k·depth − c·v_n, 0, cap) along the contact normal, opposite forces on
// the other side spread by barycentric weights: momentum is conserved exactly up to rounding.
// Forces are summed per node with integer atomics in fixed point (u_forceScale units per N):
// integer addition is associative, so the sum does not depend on thread order. NodeUpdate adds
// and clears them. Ownership bits (GLC_OWN_*) make every vertex-face and edge-edge pair count once.
// Twin: cpu::contactForces.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_CONTACT_FORCES) buffer ContactForcesBuf { ivec4 g_contactForces[]; };

uniform uint u_candidateCount;
uniform float u_thickness;   // m
uniform float u_stiffness;   // N/m
uniform float u_damping;     // N·s/m
uniform float u_forceCap;    // N per contact
uniform float u_forceScale;  // fixed-point units per N

void addForce(uint node, vec3 f) {
    ivec3 q = ivec3(round(f * u_forceScale));
    if (q.x != 0) atomicAdd(g_contactForces[node].x, q.x);
    if (q.y != 0) atomicAdd(g_contactForces[node].y, q.y);
    if (q.z != 0) atomicAdd(g_contactForces[node].z, q.z);
}

// Normal force magnitude: penalty on the depth, damping on the normal speed (separating > 0),
// never pulling, never above the cap.
float normalForce(float depth, float normalSpeed) {
    return clamp(u_stiffness * depth - u_damping * normalSpeed, 0.0, u_forceCap);
}

// Whether vertex p's contact with the face (nodes `face`, ownership bits `owned`) at barycentric
// weights `w` (exact zeros from closestOnTriangle's vertex and edge regions) counts here: the
// interior always; the edge opposite vertex k (w[k] = 0) if the face owns it; vertex k (w[k] = 1)
// if the face owns it and p < that node — the same vertex-vertex contact is also found from the
// other side (that node against p's face), and counts once.
bool ownsClosestFeature(uint p, uvec3 face, vec3 w, uint owned) {
    uint zeros = uint(w.x == 0.0) + uint(w.y == 0.0) + uint(w.z == 0.0);
    if (zeros == 0u) return true;
    for (uint k = 0u; k < 3u; ++k) {
        if (zeros == 2u && w[k] == 1.0) return (owned & (GLC_OWN_VERTEX0 << k)) != 0u && p < face[k];
        if (zeros == 1u && w[k] == 0.0) return (owned & (GLC_OWN_EDGE01 << ((k + 1u) % 3u))) != 0u;
    }
    return true; // not reached: two zeros make the third weight 1
}

// Vertex `p` against face (a, b, c) with ownership bits `faceOwned`. Returns 1 when a force was applied.
uint vertexFace(uint p, uvec3 face, uint faceOwned, bool closed) {
    vec3 x = g_positions[p].xyz;
    vec3 xa = g_positions[face.x].xyz, xb = g_positions[face.y].xyz, xc = g_positions[face.z].xyz;
    vec3 n = cross(xb - xa, xc - xa);
    float area2 = length(n);
    if (!(area2 > 0.0)) return 0u; // zero-area face: its edges still take part in edge-edge
    n /= area2;
    vec3 w = closestOnTriangle(x, xa, xb, xc);
    if (!ownsClosestFeature(p, face, w, faceOwned)) return 0u;
    vec3 diff = x - (w.x * xa + w.y * xb + w.z * xc);
    float d = length(diff);
    float s = dot(n, x - xa);
    bool inside = w.x > 0.0 && w.y > 0.0 && w.z > 0.0;
    vec3 u;
    float depth;
    if (closed && inside && s < u_thickness && s > -u_thickness) {
        u = n;
        depth = u_thickness - s;
    } else if (d < u_thickness && d > 0.0) {
        u = diff / d;
        depth = u_thickness - d;
    } else {
        return 0u;
    }
    vec3 vRel = g_velocities[p].xyz -
                (w.x * g_velocities[face.x].xyz + w.y * g_velocities[face.y].xyz + w.z * g_velocities[face.z].xyz);
    float f = normalForce(depth, dot(vRel, u));
    if (f <= 0.0) return 0u;
    vec3 F = f * u;
    addForce(p, F);
    addForce(face.x, -w.x * F);
    addForce(face.y, -w.y * F);
    addForce(face.z, -w.z * F);
    return 1u;
}

uint edgeEdge(uint p0, uint p1, uint q0, uint q1) {
    vec3 x0 = g_positions[p0].xyz, x1 = g_positions[p1].xyz;
    vec3 y0 = g_positions[q0].xyz, y1 = g_positions[q1].xyz;
    vec2 st = closestSegmentParams(x0, x1, y0, y1);
    if (!(st.x > 0.0 && st.x < 1.0 && st.y > 0.0 && st.y < 1.0)) return 0u;
    vec3 diff = mix(x0, x1, st.x) - mix(y0, y1, st.y);
    float d = length(diff);
    if (!(d < u_thickness) || !(d > 0.0)) return 0u;
    vec3 u = diff / d;
    vec3 vRel = mix(g_velocities[p0].xyz, g_velocities[p1].xyz, st.x) -
                mix(g_velocities[q0].xyz, g_velocities[q1].xyz, st.y);
    float f = normalForce(u_thickness - d, dot(vRel, u));
    if (f <= 0.0) return 0u;
    vec3 F = f * u;
    addForce(p0, (1.0 - st.x) * F);
    addForce(p1, st.x * F);
    addForce(q0, -(1.0 - st.y) * F);
    addForce(q1, -st.y * F);
    return 1u;
}

void main() {
    uint i = globalIndex();
    if (i >= u_candidateCount) return;
    uvec2 pair = g_facePairs[i];
    uvec3 fa = faceNodes(pair.x), fb = faceNodes(pair.y);
    GpuFaceInfo ia = g_faceInfo[pair.x];
    GpuFaceInfo ib = g_faceInfo[pair.y];
    bool closedA = g_objects[ia.object].closed != 0u;
    bool closedB = g_objects[ib.object].closed != 0u;
    uint contacts = 0u;
    for (uint k = 0u; k < 3u; ++k) {
        if ((ia.owned & (GLC_OWN_VERTEX0 << k)) != 0u) contacts += vertexFace(fa[k], fb, ib.owned, closedB);
        if ((ib.owned & (GLC_OWN_VERTEX0 << k)) != 0u) contacts += vertexFace(fb[k], fa, ia.owned, closedA);
    }
    for (uint e = 0u; e < 3u; ++e) {
        if ((ia.owned & (GLC_OWN_EDGE01 << e)) == 0u) continue;
        for (uint g = 0u; g < 3u; ++g) {
            if ((ib.owned & (GLC_OWN_EDGE01 << g)) == 0u) continue;
            contacts += edgeEdge(fa[e], fa[(e + 1u) % 3u], fb[g], fb[(g + 1u) % 3u]);
        }
    }
    if (contacts != 0u) atomicAdd(g_counters.contactCount, contacts);
}
