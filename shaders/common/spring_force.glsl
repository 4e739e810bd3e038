// The springs' force on node i over the entries [first, end) of its row, every `stride`-th:
// Hooke plus damping along each spring, in the row's order (deterministic, no atomics). Shared by
// SpringUpdate and FrameStep. Include after g_positions, g_velocities, g_springs and
// g_nodeSpringList are declared. Twin: cpu::springUpdate.
vec3 springForce(uint i, uint first, uint end, uint stride) {
    vec3 xi = g_positions[i].xyz;
    vec3 vi = g_velocities[i].xyz;
    vec3 f = vec3(0.0);
    for (uint k = first; k < end; k += stride) {
        GpuSpring s = g_springs[g_nodeSpringList[k]];
        uint j = (s.nodeA == i) ? s.nodeB : s.nodeA;
        vec3 d = g_positions[j].xyz - xi;
        float len = length(d);
        if (len <= 0.0) continue; // coincident ends: no direction, no force
        vec3 dir = d / len;
        float magnitude = s.stiffness * (len - s.restLength) + s.damping * dot(g_velocities[j].xyz - vi, dir);
        f += magnitude * dir;
    }
    return f;
}
