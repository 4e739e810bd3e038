#version 430 core
// glcollide-features: GLC_SPRINGS GLC_GRAVITY GLC_DAMPING GLC_WIND GLC_IMPLICIT_GROUND
// ImplicitNewtonSetup — the second Newton step of one backward Euler substep (decision 0024,
// "Contacts that enter during the substep"), from the first step's result: x1 = x0 + h·v1 bound
// as the positions, v1 as the velocities, v0 (the velocities the first step started from) copied
// into the residual buffer before the dispatch (each node's r is written over its v0 after it is
// read: a separate block would be a 17th with wind, above GL's minimum of 16). A and P are assembled at x1 exactly as ImplicitSetup does,
// with the contacts found at x1, and
//   b = h·f(x1, v1) − m·(v1 − v0),   v = v1 + δ after the conjugate gradients,
// the residual of backward Euler M(v − v0) = h·f(x0 + h·v, v) at v1 (the stiffness term belongs to
// the first step's linearisation at x0 and is not used). Twin: cpu::implicitNewtonChangeDense / implicitNewtonRightHandSide.
#define GLC_IMPLICIT_CONTACTS
#define GLC_RESIDUAL_ACCESS
#include "common/implicit_setup_main.glsl"

vec3 rightHandSide(uint i, float w, vec3 f, vec3 stiffnessTerm) {
    vec3 startVelocity = g_residual[i].xyz; // v0 (node i's owner reads it, then writes r over it)
    return u_h * f - (1.0 / w) * (g_velocities[i].xyz - startVelocity);
}
