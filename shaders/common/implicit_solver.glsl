// Shared by the implicit Euler passes (implicit_setup, implicit_cg_direction, implicit_cg_update):
// the spring's 3x3 block, symmetric 3x3 algebra, the per-group partial sums and the solver state.
// Include after row_gather.glsl. CPU twin: cpu/implicit_twin.cpp (same formulas, double).

layout(std430, binding = GLC_BIND_SOLVER_PARTIALS_R) buffer PartialsRBuf { vec2 g_partialsR[]; };
layout(std430, binding = GLC_BIND_SOLVER_STATE) buffer SolverStateBuf { GpuSolverState g_state; };

uniform float u_h;          // s, substep length
uniform float u_massFactor; // 1 + h·c_air: the air damping's (implicit) share of the diagonal

// One spring seen from node i towards node j: h·C + h²·K = alpha·I + beta·u uᵀ with
// K = k·[u uᵀ + max(0, 1 − L/l)(I − u uᵀ)] (transverse term clamped at 0 when compressed: positive
// semidefinite) and C = c·u uᵀ; force = k(l − L) + c·u·(vj − vi) on i along u.
struct SpringTerm {
    vec3 u;
    float alpha;
    float beta;
    float force;
    float transverseStiffness; // k·max(0, 1 − L/l)
    float alongStiffness;      // k − transverseStiffness
    bool valid;                // false for coincident ends: no direction, no force (as SpringUpdate)
};

SpringTerm springTerm(GpuSpring s, vec3 xi, vec3 xj, vec3 vi, vec3 vj) {
    SpringTerm term;
    vec3 d = xj - xi;
    float len = length(d);
    term.valid = len > 0.0;
    term.u = term.valid ? d / len : vec3(0.0);
    float t = term.valid ? max(0.0, 1.0 - s.restLength / len) : 0.0;
    term.transverseStiffness = s.stiffness * t;
    term.alongStiffness = s.stiffness - term.transverseStiffness;
    term.alpha = term.valid ? u_h * u_h * term.transverseStiffness : 0.0;
    term.beta = term.valid ? u_h * s.damping + u_h * u_h * term.alongStiffness : 0.0;
    term.force = term.valid ? s.stiffness * (len - s.restLength) + s.damping * dot(vj - vi, term.u) : 0.0;
    return term;
}

// (alpha·I + beta·u uᵀ)·d
vec3 applyTerm(SpringTerm term, vec3 d) {
    return term.alpha * d + (term.beta * dot(term.u, d)) * term.u;
}

// Symmetric 3x3 as (xx, xy, xz, yy) and (yz, zz).
vec3 symMul(vec4 a, vec2 b, vec3 v) {
    return vec3(a.x * v.x + a.y * v.y + a.z * v.z, a.y * v.x + a.w * v.y + b.x * v.z,
                a.z * v.x + b.x * v.y + b.y * v.z);
}

// Inverse of a symmetric positive definite 3x3 by cofactors; returned like the input.
void symInverse(vec4 a, vec2 b, out vec4 ia, out vec2 ib) {
    float xx = a.x, xy = a.y, xz = a.z, yy = a.w, yz = b.x, zz = b.y;
    float c00 = yy * zz - yz * yz, c01 = xz * yz - xy * zz, c02 = xy * yz - xz * yy;
    float c11 = xx * zz - xz * xz, c12 = xy * xz - xx * yz, c22 = xx * yy - xy * xy;
    float invDet = 1.0 / (xx * c00 + xy * c01 + xz * c02);
    ia = vec4(c00, c01, c02, c11) * invDet;
    ib = vec2(c12, c22) * invDet;
}

// Sums of the previous pass's per-group partials, in the same order in every group (each
// invocation adds every GLC_WORKGROUP_SIZE-th one, then groupSum's tree): every group gets the
// same bits, so all agree on the step sizes and on convergence without a separate reduce pass.
uint partialCount() {
    return u_lightGroups + u_heavyCount;
}

vec2 sumPartialsR() {
    vec4 acc = vec4(0.0);
    for (uint k = gl_LocalInvocationID.x; k < partialCount(); k += GLC_WORKGROUP_SIZE) acc.xy += g_partialsR[k];
    return groupSum(acc).xy;
}

