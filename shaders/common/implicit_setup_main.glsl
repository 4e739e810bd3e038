// The body of ImplicitSetup (implicit_setup.comp) and of its Newton step
// (implicit_newton_setup.comp): the row of A and P at the bound positions, the force f and the
// stiffness term, the start of the conjugate gradients. The including kernel defines
// rightHandSide(): the one line in which the two differ, and GLC_RESIDUAL_ACCESS.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/row_gather.glsl"
#include "common/implicit_solver.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
#ifdef GLC_SPRINGS
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_NODE_SPRING_LIST) readonly buffer NodeSpringListBuf { uint g_nodeSpringList[]; };
#endif
#include "common/external_force.glsl"
#ifdef GLC_IMPLICIT_CONTACTS
#include "common/implicit_contact.glsl"

// Node i's contact row, in the sorted order of its incidence list (the same sum on every run).
struct ContactRow {
    vec3 force;                  // Σ a_i·k·depth·u
    vec3 stiffnessTimesVelocity; // Σ −k·a_i·u (u·Σ_j a_j v_j): ∂f/∂x·v, pinned nodes' v included
    vec4 blockA;                 // Σ h²k·a_i²·u uᵀ: xx xy xz yy
    vec2 blockB;                 // yz zz
};

ContactRow contactRow(uint i) {
    ContactRow row = ContactRow(vec3(0.0), vec3(0.0), vec4(0.0), vec2(0.0));
    uint end = contactRowEnd(i);
    for (uint e = contactRowBegin(i); e < end; ++e) {
        uint entry = contactEntry(e);
        GpuImplicitContact c = contactRecord(incidenceRecord(entry));
        float ai = c.weights[incidenceCorner(entry)];
        vec3 u = c.normalForce.xyz;
        vec3 vRel = c.weights.x * g_velocities[c.nodes.x].xyz + c.weights.y * g_velocities[c.nodes.y].xyz +
                    c.weights.z * g_velocities[c.nodes.z].xyz + c.weights.w * g_velocities[c.nodes.w].xyz;
        row.force += (ai * c.normalForce.w) * u;
        row.stiffnessTimesVelocity -= (u_contactStiffness * ai * dot(u, vRel)) * u;
        float block = u_h * u_h * u_contactStiffness * ai * ai;
        row.blockA += block * vec4(u.x * u.x, u.x * u.y, u.x * u.z, u.y * u.y);
        row.blockB += block * vec2(u.y * u.z, u.z * u.z);
    }
    return row;
}
#endif
// GLC_RESIDUAL_ACCESS: writeonly, or empty where rightHandSide() reads the buffer first (the
// Newton step finds v0 there).
layout(std430, binding = GLC_BIND_SOLVER_RESIDUAL) GLC_RESIDUAL_ACCESS buffer ResidualBuf { vec4 g_residual[]; };
layout(std430, binding = GLC_BIND_SOLVER_PRECONDITIONED) writeonly buffer PreconditionedBuf { vec4 g_preconditioned[]; };
layout(std430, binding = GLC_BIND_SOLVER_DIRECTION_OUT) writeonly buffer DirectionOutBuf { vec4 g_direction[]; };
layout(std430, binding = GLC_BIND_SOLVER_BLOCK_INVERSE) writeonly buffer BlockInverseBuf { float g_blockInverse[]; };

// b for node i (free, inverse mass w) from its force f and stiffness term Σ ∂f/∂x·v: defined by
// the kernel that includes this file (implicit_setup.comp, implicit_newton_setup.comp).
vec3 rightHandSide(uint i, float w, vec3 f, vec3 stiffnessTerm);

#ifdef GLC_IMPLICIT_GROUND
uniform float u_groundStiffness; // N/m per node
uniform float u_groundLevel;     // m: the ground's height plus its band
#endif

void main() {
    if (groupIsPadding()) return; // whole groups only: the rest meet at barriers
    RowTask task = rowTask();
    uint i = task.node;
    float w = task.gathers ? g_positions[i].w : 0.0;

    // This invocation's share of the row: spring force, K·(v_j − v_i), and the diagonal block.
    vec3 force = vec3(0.0), stiffnessTimesVelocity = vec3(0.0);
    vec4 blockA = vec4(0.0); // xx xy xz yy
    vec2 blockB = vec2(0.0); // yz zz
#ifdef GLC_SPRINGS
    if (w > 0.0) {
        vec3 xi = g_positions[i].xyz, vi = g_velocities[i].xyz;
        for (uint k = task.firstSpring; k < rowEnd(task); k += task.stride) {
            GpuSpring s = g_springs[g_nodeSpringList[k]];
            uint j = (s.nodeA == i) ? s.nodeB : s.nodeA;
            vec3 vj = g_velocities[j].xyz;
            SpringTerm term = springTerm(s, xi, g_positions[j].xyz, vi, vj);
            if (!term.valid) continue;
            force += term.force * term.u;
            vec3 dv = vj - vi;
            stiffnessTimesVelocity += term.transverseStiffness * dv + (term.alongStiffness * dot(term.u, dv)) * term.u;
            vec3 u = term.u;
            blockA += vec4(term.alpha, 0.0, 0.0, term.alpha) + term.beta * vec4(u.x * u.x, u.x * u.y, u.x * u.z, u.y * u.y);
            blockB += vec2(0.0, term.alpha) + term.beta * vec2(u.y * u.z, u.z * u.z);
        }
    }
#endif
    vec4 sum0 = rowSum(vec4(force, blockB.x));
    vec4 sum1 = rowSum(vec4(stiffnessTimesVelocity, blockB.y));
    vec4 sum2 = rowSum(blockA);

    vec2 partial = vec2(0.0);
    if (task.owner) {
        vec3 r = vec3(0.0), z = vec3(0.0);
        vec4 inverseA = vec4(0.0);
        vec2 inverseB = vec2(0.0);
        vec3 f = sum0.xyz + externalForce(i);
        if (w > 0.0) {
            float m = u_massFactor / w;
            vec4 a = sum2 + vec4(m, 0.0, 0.0, m);
            vec2 b = vec2(sum0.w, sum1.w + m);
            vec3 stiffnessTerm = sum1.xyz;
#ifdef GLC_IMPLICIT_CONTACTS
            ContactRow contacts = contactRow(i);
            f += contacts.force;
            stiffnessTerm += contacts.stiffnessTimesVelocity;
            a += contacts.blockA;
            b += contacts.blockB;
#endif
#ifdef GLC_IMPLICIT_GROUND
            // The ground as a penalty below u_groundLevel (height + band): force k_g·depth up, its
            // stiffness −k_g·e_y e_yᵀ into the matrix and the right-hand side (decision 0024).
            float groundDepth = u_groundLevel - g_positions[i].y;
            if (groundDepth > 0.0) {
                f.y += u_groundStiffness * groundDepth;
                stiffnessTerm.y -= u_groundStiffness * g_velocities[i].y;
                a.w += u_h * u_h * u_groundStiffness;
            }
#endif
            symInverse(a, b, inverseA, inverseB);
            r = rightHandSide(i, w, f, stiffnessTerm);
            z = symMul(inverseA, inverseB, r);
            partial = vec2(dot(r, z), dot(r, r));
        }
        g_residual[i] = vec4(r, 0.0);
        g_preconditioned[i] = vec4(z, 0.0);
        g_direction[i] = vec4(z, 0.0);
        g_blockInverse[6u * i] = inverseA.x;
        g_blockInverse[6u * i + 1u] = inverseA.y;
        g_blockInverse[6u * i + 2u] = inverseA.z;
        g_blockInverse[6u * i + 3u] = inverseA.w;
        g_blockInverse[6u * i + 4u] = inverseB.x;
        g_blockInverse[6u * i + 5u] = inverseB.y;
    }
    vec2 groupPartial = groupSum(vec4(partial, 0.0, 0.0)).xy;
    if (gl_LocalInvocationID.x == 0u) {
        g_partialsR[groupIndex()] = groupPartial;
        if (groupIndex() == 0u) g_state.doneAt = GLC_SOLVER_RUNNING;
    }
}
