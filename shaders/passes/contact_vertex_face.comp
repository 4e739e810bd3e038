#version 430 core
// ContactResponse, vertex-face — one invocation per entry (node p, face) of GLC_LIST_VERTEX_FACE
// (indirect dispatch from its count; the pairs come from FeaturePairs, feature_pairs.comp): within
// the thickness h, p is pushed away from its closest point on the face. For a face of a closed
// object (outward normals) a vertex whose projection lies inside the face and that is at most h
// below it is pushed out along the normal, so a shallow penetration is undone, not deepened.
// A vertex near an edge or a vertex of the other mesh is near every face around that feature:
// the contact counts only for the face that owns the closest feature (GLC_OWN_* bits), and a
// vertex-vertex contact only from its lower node, so a vertex meeting a vertex of valence 6 gets
// one contact, not twelve (the stiffness the substep rule assumes; six gave the soak scene's
// energy gain, docs/collisions.md). Force law and fixed-point sums: common/contact_force.glsl.
// Twin: cpu::contactForces.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"
#include "common/contact_force.glsl"

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };

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

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_VERTEX_FACE)) return;
    uvec2 item = g_vertexFace[i]; // (node, face)
    GpuFaceInfo info = g_faceInfo[item.y];
    bool closed = g_objects[info.object].closed != 0u;
    if (vertexFace(item.x, faceNodes(item.y), info.owned, closed) != 0u) atomicAdd(g_counters.contactCount, 1u);
}
