#version 430 core
// glcollide-features: GLC_SPRINGS GLC_IMPLICIT_CONTACTS GLC_IMPLICIT_GROUND
// ImplicitCgDirection — iteration u_iteration of the implicit solver's conjugate gradients, first
// width: from the previous pass's partial sums of r·z and r·r every group computes the same
// rz and ‖r‖²; if ‖r‖ ≤ tolerance·‖b‖ (or the cap is reached) the solve is over and invocation 0
// records the statistics. Otherwise the new direction p = z + beta·p (beta = rz / previous rz) and
// its product q = A·p, with A·p at node i = m(1 + h·c_air)·p_i + Σ (h·C_s + h²·K_s)(p_i − p_j);
// a neighbour's new p_j is formed from its z_j and old p_j on the fly (p is double-buffered).
// With GLC_IMPLICIT_CONTACTS every contact of the node's sorted incidence list adds
// h²k·a_i·u (u·Σ_j a_j p_j) (pinned nodes' p_j are 0: they are not part of the system).
// Per-group partial sums of p·q for ImplicitCgUpdate. Twin: cpu::implicitVelocityUpdate.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/row_gather.glsl"
#include "common/implicit_solver.glsl"
#include "common/implicit_pq.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
#ifdef GLC_SPRINGS
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_NODE_SPRING_LIST) readonly buffer NodeSpringListBuf { uint g_nodeSpringList[]; };
#endif
layout(std430, binding = GLC_BIND_SOLVER_PRECONDITIONED) readonly buffer PreconditionedBuf { vec4 g_preconditioned[]; };
layout(std430, binding = GLC_BIND_SOLVER_DIRECTION_IN) readonly buffer DirectionInBuf { vec4 g_directionIn[]; };
layout(std430, binding = GLC_BIND_SOLVER_DIRECTION_OUT) writeonly buffer DirectionOutBuf { vec4 g_directionOut[]; };
layout(std430, binding = GLC_BIND_SOLVER_PRODUCT) writeonly buffer ProductBuf { vec4 g_product[]; };

#ifdef GLC_IMPLICIT_CONTACTS
#include "common/implicit_contact.glsl"

// Node j's new direction p_j = z_j + beta·p_j (0 for a pinned node: its z and p are 0).
vec3 newDirection(uint j, float beta) {
    return g_preconditioned[j].xyz + beta * g_directionIn[j].xyz;
}

// Σ over node i's contacts, in the sorted order of its incidence list, of h²k·a_i·u (u·Σ_j a_j p_j).
vec3 contactProduct(uint i, float beta) {
    vec3 product = vec3(0.0);
    uint end = contactRowEnd(i);
    for (uint e = contactRowBegin(i); e < end; ++e) {
        uint entry = contactEntry(e);
        GpuImplicitContact c = contactRecord(incidenceRecord(entry));
        float ai = c.weights[incidenceCorner(entry)];
        vec3 u = c.normalForce.xyz;
        vec3 pRel = c.weights.x * newDirection(c.nodes.x, beta) + c.weights.y * newDirection(c.nodes.y, beta) +
                    c.weights.z * newDirection(c.nodes.z, beta) + c.weights.w * newDirection(c.nodes.w, beta);
        product += (u_h * u_h * u_contactStiffness * ai * dot(u, pRel)) * u;
    }
    return product;
}
#endif

uniform uint u_iteration;     // k = 0, 1, …, u_maxIterations (the last one only checks)
uniform uint u_maxIterations; // the cap
uniform float u_inverseTolerance2; // 1/tolerance²

#ifdef GLC_IMPLICIT_GROUND
uniform float u_groundStiffness; // N/m per node
uniform float u_groundLevel;     // m: the ground's height plus its band
#endif

void main() {
    if (groupIsPadding()) return; // whole groups only: the rest meet at barriers
    uint k = u_iteration;
    vec2 rz_rr = sumPartialsR(); // the same bits in every group
    float rhsNormSquared = (k == 0u) ? rz_rr.y : g_state.rhsNormSquared;
    // ‖r‖ ≤ tolerance·‖b‖, tested as ‖r‖²/tolerance² ≤ ‖b‖²: near rest ‖b‖² can be so small that
    // tolerance²·‖b‖² underflows to 0 (found by the oscillator benchmark), which ‖r‖²/tolerance², larger
    // than ‖r‖², cannot. Also over when r·z is no longer positive: the residual has flushed to zero
    // and the next beta would divide by it (0/0 = NaN). No absolute floor: the answers do not depend
    // on the units of length or mass (an absolute floor of 10⁻³⁰ kg²m²/s² stopped a scene drawn at
    // 2⁻¹² of its size earlier than the same scene in metres: UnitsGl).
    bool converged = rz_rr.y * u_inverseTolerance2 <= rhsNormSquared || rz_rr.x <= 0.0;
    bool over = converged || k >= u_maxIterations;
    if (groupIndex() == 0u && gl_LocalInvocationID.x == 0u) {
        if (k == 0u) g_state.rhsNormSquared = rz_rr.y;
        g_state.rz[k & 1u] = rz_rr.x;
        if (over && g_state.doneAt == GLC_SOLVER_RUNNING) {
            g_state.doneAt = k;
            float residual = rhsNormSquared > 0.0 ? sqrt(rz_rr.y / rhsNormSquared) : 0.0;
            atomicMax(g_state.maxIterations, k);
            atomicMax(g_state.maxResidualBits, floatBitsToUint(residual));
            atomicAdd(g_state.totalIterations, k);
            if (!converged) atomicAdd(g_state.unconvergedSubsteps, 1u);
        }
    }
    if (over) return; // uniform: every group computed the same rz_rr

    float beta = (k == 0u) ? 0.0 : rz_rr.x / g_state.rz[(k - 1u) & 1u];
    RowTask task = rowTask();
    uint i = task.node;
    float w = task.gathers ? g_positions[i].w : 0.0;
    vec3 pi = task.gathers ? g_preconditioned[i].xyz + beta * g_directionIn[i].xyz : vec3(0.0);
    vec3 product = vec3(0.0);
#ifdef GLC_SPRINGS
    if (w > 0.0) {
        vec3 xi = g_positions[i].xyz;
        for (uint s = task.firstSpring; s < rowEnd(task); s += task.stride) {
            GpuSpring spring = g_springs[g_nodeSpringList[s]];
            uint j = (spring.nodeA == i) ? spring.nodeB : spring.nodeA;
            SpringTerm term = springTerm(spring, xi, g_positions[j].xyz, vec3(0.0), vec3(0.0));
            if (!term.valid) continue;
            // A pinned neighbour's z and p are 0, so its p_j is 0: it is not part of the system.
            vec3 pj = g_preconditioned[j].xyz + beta * g_directionIn[j].xyz;
            product += applyTerm(term, pi - pj);
        }
    }
#endif
    vec3 q = rowSum(vec4(product, 0.0)).xyz;
    float partial = 0.0;
    if (task.owner) {
        if (w > 0.0) {
            q += (u_massFactor / w) * pi;
#ifdef GLC_IMPLICIT_CONTACTS
            q += contactProduct(i, beta);
#endif
#ifdef GLC_IMPLICIT_GROUND
            if (u_groundLevel - g_positions[i].y > 0.0) q.y += u_h * u_h * u_groundStiffness * pi.y;
#endif
        } else {
            q = vec3(0.0);
            pi = vec3(0.0);
        }
        g_directionOut[i] = vec4(pi, 0.0);
        g_product[i] = vec4(q, 0.0);
        partial = dot(pi, q);
    }
    float groupPartial = groupSum(vec4(partial, 0.0, 0.0, 0.0)).x;
    if (gl_LocalInvocationID.x == 0u) g_partialsPq[groupIndex()] = groupPartial;
}
