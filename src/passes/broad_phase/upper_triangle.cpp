#include "passes/broad_phase/upper_triangle.hpp"

#include <epoxy/gl.h>

#include <algorithm>

namespace glcollide::passes {

void dispatchUpperTriangle(const gl::ComputeProgram& program, std::uint32_t n, std::uint32_t tile) {
    constexpr std::uint32_t kMaxGroups = 65535; // GL 4.3 minimum of GL_MAX_COMPUTE_WORK_GROUP_COUNT
    if (n == 0) return;
    program.use();
    const std::uint32_t groups = (n + tile - 1) / tile;
    for (std::uint32_t gy = 0; gy < groups; gy += kMaxGroups) {
        const std::uint32_t ny = std::min(kMaxGroups, groups - gy);
        // Chunks wholly below the diagonal hold no invocation with x >= y.
        for (std::uint32_t gx = gy; gx < groups; gx += kMaxGroups) {
            const std::uint32_t nx = std::min(kMaxGroups, groups - gx);
            program.set("u_tileOriginX", gx * tile);
            program.set("u_tileOriginY", gy * tile);
            gl::ComputeProgram::dispatch(nx, ny, 1);
        }
        if (gy + ny >= groups) break;
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace glcollide::passes
