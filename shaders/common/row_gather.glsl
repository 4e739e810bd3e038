// Work-group layout of the passes that gather each node's spring row (SpringUpdate and the
// implicit solver). Include after the layout(local_size_x) declaration.
//
// Groups [0, u_lightGroups) give one invocation per node; a node with more than GLC_HEAVY_ROW
// springs is skipped there. Group u_lightGroups + h gathers heavy node g_heavyNodes[h]: its
// GLC_WORKGROUP_SIZE invocations take every GLC_WORKGROUP_SIZE-th spring and add their sums in a
// fixed tree (groupSum). So no invocation walks more than GLC_HEAVY_ROW springs while the others of
// its group wait, and every sum is in a fixed order (deterministic, no float atomics).

layout(std430, binding = GLC_BIND_NODE_SPRING_OFFSETS) readonly buffer NodeSpringOffsetsBuf { uint g_nodeSpringOffsets[]; };
layout(std430, binding = GLC_BIND_HEAVY_NODES) readonly buffer HeavyNodesBuf { uint g_heavyNodes[]; };

uniform uint u_nodeCount;
uniform uint u_lightGroups; // ceil(nodes / GLC_WORKGROUP_SIZE)
uniform uint u_heavyCount;  // nodes with more than GLC_HEAVY_ROW springs

shared vec4 s_groupSum[GLC_WORKGROUP_SIZE];

// The flat work-group index of a dispatch that may spill into y (ComputeProgram::dispatch1D).
uint groupIndex() {
    return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
}

// Groups past the last heavy node exist only because a large dispatch is rounded up to a 2D grid.
bool groupIsPadding() {
    return groupIndex() >= u_lightGroups + u_heavyCount;
}

bool groupIsHeavy() {
    return groupIndex() >= u_lightGroups;
}

bool rowIsHeavy(uint node) {
    return g_nodeSpringOffsets[node + 1u] - g_nodeSpringOffsets[node] > GLC_HEAVY_ROW;
}

// The node this invocation works on, and whether it is this invocation's (or group's) to gather.
struct RowTask {
    uint node;
    bool gathers;      // the node exists and this layout gathers it
    uint firstSpring; // this invocation's first entry of the row
    uint stride;      // 1 for a light node, GLC_WORKGROUP_SIZE for a heavy node
    bool owner;       // writes the node's results (light: itself; heavy: invocation 0)
};

RowTask rowTask() {
    RowTask task;
    uint lane = gl_LocalInvocationID.x;
    if (groupIsHeavy()) {
        task.node = g_heavyNodes[groupIndex() - u_lightGroups];
        task.gathers = true;
        task.firstSpring = g_nodeSpringOffsets[task.node] + lane;
        task.stride = GLC_WORKGROUP_SIZE;
        task.owner = lane == 0u;
    } else {
        task.node = groupIndex() * GLC_WORKGROUP_SIZE + lane;
        task.gathers = task.node < u_nodeCount && !rowIsHeavy(task.node);
        task.firstSpring = task.gathers ? g_nodeSpringOffsets[task.node] : 0u;
        task.stride = 1u;
        task.owner = task.gathers;
    }
    return task;
}

uint rowEnd(RowTask task) {
    return task.gathers ? g_nodeSpringOffsets[task.node + 1u] : 0u;
}

// Sum of v over the work group, the same fixed tree in every group. Every invocation of the
// group must call it (it has barriers).
vec4 groupSum(vec4 v) {
    uint lane = gl_LocalInvocationID.x;
    s_groupSum[lane] = v;
    memoryBarrierShared();
    barrier();
    for (uint width = GLC_WORKGROUP_SIZE / 2u; width > 0u; width >>= 1u) {
        if (lane < width) s_groupSum[lane] += s_groupSum[lane + width];
        memoryBarrierShared();
        barrier();
    }
    vec4 sum = s_groupSum[0];
    // The next call overwrites s_groupSum[0]: every invocation must have read it first. Without
    // the memory barrier llvmpipe let the read slip past barrier() (the 0/8 split of a group showed
    // two different sums).
    memoryBarrierShared();
    barrier();
    return sum;
}

// In a heavy group, the row's sum (every invocation holds its share); in a light group, v itself.
vec4 rowSum(vec4 v) {
    return groupIsHeavy() ? groupSum(v) : v;
}
