#version 430 core
// glcollide-features: GLC_SPRINGS GLC_GRAVITY GLC_DAMPING GLC_WIND GLC_IMPLICIT_CONTACTS GLC_IMPLICIT_GROUND
// ImplicitSetup — assembles one implicit Euler substep's system A·Δv = b per node (Baraff &
// Witkin 1998, one Newton step of backward Euler) and starts the conjugate gradients at Δv = 0:
//   b = h·f + h²·Σ K_s (v_j − v_i),   P = m(1 + h·c_air)·I + Σ (h·C_s + h²·K_s)  (A's diagonal block)
//   r = b,  z = P⁻¹·r,  p = z,  per-group partial sums of r·z and r·r.
// f is the external force (gravity, air damping, wind: common/external_force.glsl) and the springs'
// force (GLC_SPRINGS). With GLC_IMPLICIT_CONTACTS the active contacts of the incidence list
// (common/implicit_contact.glsl) add their penalty force a_i·k·depth·u to f, −k·a_i·u(u·Σ a_j v_j) to
// the stiffness term and h²k·a_i²·u uᵀ to P; without it contacts come after the solve
// (ContactResponse, then NodeUpdate). Pinned nodes (w = 0) get zeros everywhere: their Δv stays 0.
// Twin: cpu::implicitVelocityUpdate.
#define GLC_RESIDUAL_ACCESS writeonly
#include "common/implicit_setup_main.glsl"

vec3 rightHandSide(uint i, float w, vec3 f, vec3 stiffnessTerm) {
    return u_h * f + (u_h * u_h) * stiffnessTerm;
}
