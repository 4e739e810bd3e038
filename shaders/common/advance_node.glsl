// One symplectic Euler substep of node i under force f (v += h·w·f; x += h·v), a pinned node
// (w = 0) held, the optional ground plane with restitution and Coulomb friction on the velocity,
// and the optional non-finite check. Shared by NodeUpdate and FrameStep. Include after
// g_positions and g_velocities (and, with GLC_CHECK_FINITE, g_health) are declared.
// Twin: cpu::nodeUpdate.
uniform float u_h; // s
#ifdef GLC_GROUND
uniform float u_groundHeight; // m
uniform float u_restitution;
uniform float u_friction;
#endif

// The two halves of the step, written once: NodeUpdate runs both in one invocation, continuous
// detection runs the velocity half (with the prediction x1 = x + h·v) in NodePredict before the
// collision stages and the position half in NodeUpdate after them.
vec3 advancedVelocity(vec3 v, float w, vec3 f) {
    return v + (u_h * w) * f;
}
vec3 advancedPosition(vec3 x, vec3 v) {
    return x + u_h * v;
}

#ifdef GLC_GROUND
#include "common/ground_response.glsl"

void groundResponse(inout vec3 v) {
    groundResponse(v, u_restitution, u_friction);
}

// The ground plane: a node below it is put on it, with the velocity response.
void applyGround(inout vec3 x, inout vec3 v) {
    if (!(x.y < u_groundHeight)) return; // (a NaN is left alone, as before)
    x.y = u_groundHeight;
    groundResponse(v);
}
#endif

#ifdef GLC_CHECK_FINITE
// Records node i if x or v is not finite: infinity and NaN are the floats whose 8 exponent bits
// are all ones.
void checkFinite(uint i, vec3 x, vec3 v, uint substep) {
    const uint exponent = 0x7F800000u;
    if (any(equal(floatBitsToUint(x) & exponent, uvec3(exponent))) ||
        any(equal(floatBitsToUint(v) & exponent, uvec3(exponent)))) {
        // An earlier substep of this frame (or an earlier frame, already reported) wrote a lower
        // index: keep it.
        if (g_health.badSubstep >= substep) {
            atomicMin(g_health.firstBadNode, i);
            atomicMin(g_health.badSubstep, substep);
        }
    }
}
#endif

void advanceNode(uint i, vec3 f, uint substep) {
    vec4 p = g_positions[i];
    float w = p.w;
    if (w <= 0.0) {
        g_velocities[i] = vec4(0.0);
        return;
    }
    vec3 v = advancedVelocity(g_velocities[i].xyz, w, f);
    vec3 x = advancedPosition(p.xyz, v);
#ifdef GLC_GROUND
    applyGround(x, v);
#endif
    g_positions[i] = vec4(x, w);
    g_velocities[i] = vec4(v, 0.0);
#ifdef GLC_CHECK_FINITE
    checkFinite(i, x, v, substep);
#endif
}
