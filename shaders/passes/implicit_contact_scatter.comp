#version 430 core
// ImplicitContactScatter — the contact term of the implicit solve, step 3 of 4: one invocation per
// record (u_records of them, the count ImplicitContactFind reached); every row of the record
// (hasRow) gets the entry 4·r + corner in its node's segment. The position within the segment comes
// from an atomic decrement of the node's count (which ImplicitContactFind raised by exactly the rows
// written here, so every count ends at 0 and no entry is left unwritten); it depends on thread
// order, which ImplicitContactSort then removes.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/implicit_contact.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_CONTACT_COUNTS) buffer NodeContactCountsBuf { uint g_nodeContactCounts[]; };

uniform uint u_records; // records stored

void main() {
    uint r = globalIndex();
    if (r >= u_records) return;
    GpuImplicitContact c = contactRecord(r);
    for (uint k = 0u; k < 4u; ++k) {
        uint node = c.nodes[k];
        if (!hasRow(c, k, g_positions[node].w)) continue;
        uint position = atomicAdd(g_nodeContactCounts[node], 0xFFFFFFFFu) - 1u; // count − 1, …, 0
        setContactEntry(contactRowBegin(node) + position, 4u * r + k);
    }
}
