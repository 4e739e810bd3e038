#version 430 core
// RadialGhostNodes — the ghost nodes of radial view-based culling (docs/culling.md, "Ghost
// triangles" and "Clusters"): one invocation per ghost node, its position at the start of the
// substep (the positions x0) and at its end (the predicted positions x1), placed from its loop's
// frame (mean, unit vector area, radius; sums in loop order, so the result does not depend on
// scheduling): the mean of the loop (a fan over a hole), or for a cluster's outer loop an apex or a
// skirt node behind it — the same arithmetic as model::ghostNodePosition, in float. A cluster's
// apex also places the cluster's observer. The ghosts then move with their loop; classification
// assumes a ghost node moves linearly between the two, which defines the ghost surface during the
// substep (any closing surface serves the theorem of decision 0025). Nothing here needs to be
// exact: every later decision reads these stored floats.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; };
// Per ghost node two uvec4 (loop's first entry, count, kind, hang) and (depth bits, the observer it
// places, that observer's depth bits, unused), then the loop nodes (passes/radial_culling.cpp).
layout(std430, binding = GLC_BIND_RADIAL_GHOST_LOOPS) readonly buffer RadialGhostLoopsBuf { uint g_table[]; };
layout(std430, binding = GLC_BIND_RADIAL_GHOST_POSITIONS) writeonly buffer RadialGhostPositionsBuf { vec4 g_ghostPositions[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVER_NODES) readonly buffer RadialObserverNodesBuf { uvec4 g_observerNodes[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVERS) writeonly buffer RadialObserversBuf { vec4 g_observers[]; };

uniform uint u_ghostNodeCount;

// A loop's frame at one end of the substep (model::loopFrame): its mean, its unit vector area
// (Newell's sum about the mean; zero without area) and its largest distance from the mean.
vec3 loopPosition(bool atEnd, uint k) {
    uint node = g_table[k];
    return atEnd ? g_end[node].xyz : g_start[node].xyz;
}

void loopFrame(bool atEnd, uint first, uint count, out vec3 mean, out vec3 axis, out float radius) {
    mean = vec3(0.0);
    for (uint k = 0u; k < count; ++k) mean += loopPosition(atEnd, first + k);
    mean /= float(max(count, 1u));
    vec3 area = vec3(0.0);
    radius = 0.0;
    for (uint k = 0u; k < count; ++k) {
        vec3 a = loopPosition(atEnd, first + k) - mean;
        area += cross(a, loopPosition(atEnd, first + (k + 1u) % count) - mean);
        radius = max(radius, length(a));
    }
    float size = length(area);
    axis = size > 0.0 ? area / size : vec3(0.0);
}

void main() {
    uint ghost = globalIndex();
    if (ghost >= u_ghostNodeCount) return;
    uvec4 loop = uvec4(g_table[8u * ghost], g_table[8u * ghost + 1u], g_table[8u * ghost + 2u],
                       g_table[8u * ghost + 3u]); // first, count, kind, hang
    float depth = uintBitsToFloat(g_table[8u * ghost + 4u]);
    uint observer = g_table[8u * ghost + 5u];
    float observerDepth = uintBitsToFloat(g_table[8u * ghost + 6u]);
    for (uint end = 0u; end < 2u; ++end) {
        bool atEnd = end == 1u;
        vec3 mean, axis;
        float radius;
        loopFrame(atEnd, loop.x, loop.y, mean, axis, radius);
        vec3 position = mean; // GLC_GHOST_LOOP_MEAN
        if (loop.z == GLC_GHOST_APEX)
            position = mean - (depth * radius) * axis;
        else if (loop.z == GLC_GHOST_SKIRT)
            position = (atEnd ? g_end[loop.w].xyz : g_start[loop.w].xyz) - (depth * radius) * axis;
        g_ghostPositions[2u * ghost + end] = vec4(position, 1.0);
        if (observer != GLC_RADIAL_NO_OBSERVER) {
            // w of the start: the surface's orientation for RadialClassify (-1: its faces wind inward).
            float w = atEnd || g_observerNodes[5u * observer].z == 0u ? 1.0 : -1.0;
            g_observers[2u * observer + end] = vec4(mean - (observerDepth * radius) * axis, w);
        }
    }
}
