// Include after the layout(local_size_x) declaration. The flat invocation index of a 1D dispatch that may spill into y when it needs more than
// 65535 work groups (ComputeProgram::dispatch1D).
uint globalIndex() {
    return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
}
