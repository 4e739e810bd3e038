#version 430 core
// RadialObservers — the observer of radial view-based culling (decision 0025, docs/culling.md
// "Observers"): the centroid of its surface's nodes, or for a user observer ("User observers") the
// affine combination of its four frame nodes, at the start of the substep (the positions x0) and
// at its end (the predicted positions x1); it moves linearly between them, as the classification
// assumes (a cluster's observer, with no nodes here, is RadialGhostNodes'). A user segment
// ("Segment observers") has a frame per end; its second end goes to GLC_BIND_RADIAL_SEGMENTS (w = 1),
// which every other observer written here leaves at w = 0.
// One work group per observer; a fixed-order tree sum, so the
// point does not depend on scheduling. The start's w carries the surface's orientation (decision
// 0025, "Orientation"). Nothing here needs to be exact: an observer in a poor place
// only culls less (a surface that does not wind once around it frees no face, decision 0025).
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVER_NODES) readonly buffer RadialObserverNodesBuf { uvec4 g_observerNodes[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVERS) writeonly buffer RadialObserversBuf { vec4 g_observers[]; };
layout(std430, binding = GLC_BIND_RADIAL_SEGMENTS) writeonly buffer RadialSegmentsBuf { vec4 g_segments[]; };

shared vec3 s_start[GLC_WORKGROUP_SIZE];
shared vec3 s_end[GLC_WORKGROUP_SIZE];

// Σ w_k·x[n_k] over the frame in entries `first` (nodes) and `first + 1` (weights' bits), at
// the positions (x0) or the predicted positions (x1).
vec3 framePoint(uint first, bool atEnd) {
    uvec4 nodes = g_observerNodes[first];
    vec4 weights = uintBitsToFloat(g_observerNodes[first + 1u]);
    vec3 point = vec3(0.0);
    for (uint k = 0u; k < 4u; ++k) point += weights[k] * (atEnd ? g_end[nodes[k]].xyz : g_start[nodes[k]].xyz);
    return point;
}

void main() {
    uint observer = gl_WorkGroupID.x, i = gl_LocalInvocationID.x;
    uvec4 range = g_observerNodes[5u * observer];
    if (range.y == 0u) return; // a cluster's observer: RadialGhostNodes sets it back behind its loop
    if (range.w != 0u) {       // a user observer: its frame (and a segment's second frame)
        if (i != 0u) return;
        uint first = 5u * observer + 1u;
        g_observers[2u * observer] = vec4(framePoint(first, false), range.z != 0u ? -1.0 : 1.0);
        g_observers[2u * observer + 1u] = vec4(framePoint(first, true), 1.0);
        bool segment = range.w == 2u;
        g_segments[2u * observer] = vec4(segment ? framePoint(first + 2u, false) : vec3(0.0), segment ? 1.0 : 0.0);
        g_segments[2u * observer + 1u] = vec4(segment ? framePoint(first + 2u, true) : vec3(0.0), segment ? 1.0 : 0.0);
        return;
    }
    vec3 start = vec3(0.0), end = vec3(0.0);
    for (uint k = i; k < range.y; k += GLC_WORKGROUP_SIZE) {
        start += g_start[range.x + k].xyz;
        end += g_end[range.x + k].xyz;
    }
    s_start[i] = start;
    s_end[i] = end;
    barrier();
    for (uint half_ = GLC_WORKGROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
        if (i < half_) {
            s_start[i] += s_start[i + half_];
            s_end[i] += s_end[i + half_];
        }
        barrier();
    }
    if (i == 0u) {
        float count = float(max(range.y, 1u));
        // w: the surface's orientation for RadialClassify (-1: its faces wind inward).
        g_observers[2u * observer] = vec4(s_start[0] / count, range.z != 0u ? -1.0 : 1.0);
        g_observers[2u * observer + 1u] = vec4(s_end[0] / count, 1.0);
        g_segments[2u * observer] = vec4(0.0);
        g_segments[2u * observer + 1u] = vec4(0.0);
    }
}
