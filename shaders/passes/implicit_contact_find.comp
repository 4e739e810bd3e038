#version 430 core
// ImplicitContactFind — the contact term of the implicit solve, step 1 of 4: one invocation per
// entry of GLC_LIST_VERTEX_FACE (u_edgeEdge = 0) or GLC_LIST_EDGE_EDGE (u_edgeEdge = 1), indirect
// dispatch from the list's count. Whether the pair is a contact, and its nodes, weights, normal and
// depth, are the penalty response's (common/contact_pair.glsl, at the positions the solve is
// linearised at), evaluated with the thickness plus the margin (ContactParams::solveMargin): a pair
// within the thickness is a contact with force k·depth; a pair beyond it but within the margin that
// approaches (its relative normal velocity below −GLC_APPROACH_SLACK of its scale) gets force 0 and
// the stiffness k — the tangent quadratic bound of its penalty ½k·max(0, h − d)² at its distance
// now, which the step cannot pass without resistance (decision 0024, "Approaching pairs in the
// solve"; the engine gives the first solve a margin, its Newton steps none). With a restitution
// between bodies (ContactParams::leavingStep > 0), a pair within the thickness that bounces out of it
// within the step gets no record: its linearised penalty, two-sided, would hold it (decision 0024,
// "Restitution between bodies"). A record (an atomic
// count: exact even when the capacity is exceeded, and then the host grows the records and runs
// this again; nothing is dropped) with the penalty
// force k·depth and its pair's list slot (edge-edge: u_edgeEdgeBase + i); every node row the
// contact adds to is counted with an integer atomic (order-independent). Which record a contact
// gets depends on thread order; ImplicitContactSort orders the rows by the pair, not the record.
// Twin: cpu::implicitContacts.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"
#include "common/implicit_contact.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
layout(std430, binding = GLC_BIND_NODE_CONTACT_COUNTS) buffer NodeContactCountsBuf { uint g_nodeContactCounts[]; };

uniform float u_thickness;    // m: the band searched, the thickness plus the margin (contact_pair.glsl)
uniform float u_margin;       // m: ContactParams::solveMargin (0: contacts within the thickness only)
uniform float u_substep;      // s: the side rule's x − dt·v, as the penalty response (0: the current side)
uniform uint u_edgeEdge;      // 0: the vertex-face list, 1: the edge-edge list
uniform uint u_edgeEdgeBase;  // the first list slot of the edge-edge list: the vertex-face capacity
uniform uint u_recordCapacity; // records the buffer holds
uniform float u_leavingStep;  // s: ContactParams::leavingStep (0: every pair within the thickness)
uniform float u_leavingSpeed; // m/s: ContactParams::leavingSpeed

vec3 previousPosition(uint n) { return g_positions[n].xyz - u_substep * g_velocities[n].xyz; }

// Contacts at any depth for pairs that went through each other (common/contact_pair.glsl).
const bool kContactCrossings = true;
#include "common/contact_pair.glsl"
#include "common/tangled.glsl"

ContactPair contactOf(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i]; // (node, face)
        GpuFaceInfo info = g_faceInfo[item.y];
        return vertexFaceContact(item.x, faceNodes(item.y), info.owned, g_objects[info.object]);
    }
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
    if (faceTangled(item.x / 3u) || faceTangled(item.y / 3u)) return noContact(); // tangled.glsl
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    return edgeEdgeContact(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]);
}

// The pair's relative normal velocity at the velocities the solve is linearised at.
float normalSpeed(ContactPair pair) {
    vec3 relative = vec3(0.0);
    for (uint k = 0u; k < 4u; ++k) relative += pair.weights[k] * g_velocities[pair.nodes[k]].xyz;
    return dot(pair.normal, relative);
}

// Whether the pair closes at the velocities the solve is linearised at (GLC_APPROACH_SLACK).
bool approaching(ContactPair pair) {
    vec3 relative = vec3(0.0);
    float scale = 0.0;
    for (uint k = 0u; k < 4u; ++k) {
        vec3 v = g_velocities[pair.nodes[k]].xyz;
        relative += pair.weights[k] * v;
        scale += abs(pair.weights[k]) * length(v);
    }
    return dot(pair.normal, relative) < -float(GLC_APPROACH_SLACK) * scale;
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(u_edgeEdge != 0u ? GLC_LIST_EDGE_EDGE : GLC_LIST_VERTEX_FACE)) return;
    ContactPair pair = contactOf(i);
    if (!pair.found || !(pair.depth > 0.0)) return;
    pair.depth -= u_margin; // the depth inside the thickness itself
    if (!(pair.depth > 0.0)) {
        if (!approaching(pair)) return;
        pair.depth = 0.0; // within the margin: stiffness, no force
    } else if (u_leavingStep > 0.0) {
        float vn = normalSpeed(pair);
        if (vn > u_leavingSpeed && vn * u_leavingStep >= pair.depth) return; // a bounce leaving the thickness
    }
    uint r = atomicAdd(g_contactData[u_contactCount], 1u);
    if (r >= u_recordCapacity) return; // counted: the host grows the records and runs this again
    GpuImplicitContact c;
    c.nodes = pair.nodes;
    c.weights = pair.weights;
    c.normalForce = vec4(pair.normal, u_contactStiffness * pair.depth);
    storeContactRecord(r, c);
    setRecordSlot(r, (u_edgeEdge != 0u ? u_edgeEdgeBase : 0u) + i);
    for (uint k = 0u; k < 4u; ++k)
        if (hasRow(c, k, g_positions[c.nodes[k]].w)) atomicAdd(g_nodeContactCounts[c.nodes[k]], 1u);
}
