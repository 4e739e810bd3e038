// The per-group partial sums of p·q (written by ImplicitCgDirection, read by ImplicitCgUpdate).
// Not part of implicit_solver.glsl: the setup pass has no p·q and no storage block to spare (a
// compute shader may use 16). Include after implicit_solver.glsl.

layout(std430, binding = GLC_BIND_SOLVER_PARTIALS_PQ) buffer PartialsPqBuf { float g_partialsPq[]; };

// Sum of the partials, the same bits in every group (see sumPartialsR).
float sumPartialsPq() {
    vec4 acc = vec4(0.0);
    for (uint k = gl_LocalInvocationID.x; k < partialCount(); k += GLC_WORKGROUP_SIZE) acc.x += g_partialsPq[k];
    return groupSum(acc).x;
}
