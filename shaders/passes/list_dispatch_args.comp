#version 430 core
// Writes the glDispatchComputeIndirect arguments of one append list from its stored count, so a
// stage that consumes a list is sized on the GPU without a CPU read-back (docs/broad-phase.md,
// "Sync points"). One invocation; the host calls it before each indirect dispatch
// (passes/collision/append_lists.cpp, AppendLists::dispatchOver).
#include "common/layout.glsl"
#include "common/lists.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = GLC_BIND_DISPATCH_ARGS) writeonly buffer DispatchArgsBuf { uint g_dispatchArgs[]; };

uniform uint u_list;          // GLC_LIST_*: whose count sizes the dispatch; writes its argument slot
uniform uint u_itemsPerGroup; // list entries handled by one work group
uniform uint u_zGroups;       // groups in z (the octree expansion's slices of one box pair's work)

void main() {
    uint groups = (storedCount(u_list) + u_itemsPerGroup - 1u) / u_itemsPerGroup;
    // GL 4.3 guarantees 65535 groups per dimension; the kernels fold y back into their index.
    uint x = min(groups, 65535u);
    uint y = x == 0u ? 1u : (groups + x - 1u) / x;
    g_dispatchArgs[3u * u_list] = x;
    g_dispatchArgs[3u * u_list + 1u] = y;
    g_dispatchArgs[3u * u_list + 2u] = max(u_zGroups, 1u);
}
