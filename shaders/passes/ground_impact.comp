#version 430 core
// GroundImpact — the ground's restitution at any step (decision 0024, "Restitution at any step";
// pass: src/passes/ground_impact.hpp). One invocation per node, after SafeStep's cuts and before the
// energy guard. A node that started the substep above the ground's band and ends it in the band
// (x1 as cut) came down onto the ground within the substep; the solve (or the cut) stopped it
// there, and with it the impact's velocity. Its impact speed is its free fall from x0 to the band's
// top: vImp² = v0y² − 2·a_y·(y0 − top), v0 its velocity at the start of the substep and a_y the
// scene's gravity. An impact faster than u_restingSpeed gets the ground's velocity response at that
// speed (common/ground_response.glsl): it leaves with e·vImp upwards, unless it already leaves
// faster, and Coulomb friction takes up to μ·(1 + e)·vImp, the impact's whole normal change, off its
// tangential speed (the solve's ground penalty that stopped it has no friction). The positions are
// not changed (the CCD's check stands), and the energy guard that follows sees the new velocities:
// the node's normal kinetic energy e²·½m·vImp² is at most what its fall to the band released.
// Twin: cpu::groundImpact.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/ground_response.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_START_VELOCITIES) readonly buffer StartVelocitiesBuf { vec4 g_startVelocities[]; };

uniform uint u_nodeCount;
uniform float u_bandTop;      // m: the ground's height plus its band
uniform float u_gravityY;     // m/s²: the scene's gravity along the ground's normal (0 without gravity)
uniform float u_restitution;  // (0, 1]
uniform float u_friction;     // Coulomb μ
uniform float u_restingSpeed; // m/s: slower impacts are resting contact (no restitution)

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    vec4 x0 = g_positions[i];
    if (x0.w <= 0.0) return; // pinned
    float y0 = x0.y, y1 = g_predicted[i].y;
    if (!(y0 > u_bandTop && y1 <= u_bandTop)) return; // not come down into the band this substep
    float v0y = g_startVelocities[i].y;
    if (!(v0y < 0.0 || u_gravityY < 0.0)) return; // neither moving nor pulled towards the ground
    float impactSpeed = sqrt(max(v0y * v0y - 2.0 * u_gravityY * (y0 - u_bandTop), 0.0));
    if (!(impactSpeed > u_restingSpeed)) return;
    vec3 v = g_velocities[i].xyz;
    if (!(v.y < u_restitution * impactSpeed)) return; // already leaving faster
    v.y = -impactSpeed; // the velocity it hit the ground with, before the solve or the cut stopped it
    groundResponse(v, u_restitution, u_friction);
    g_velocities[i] = vec4(v, 0.0);
}
