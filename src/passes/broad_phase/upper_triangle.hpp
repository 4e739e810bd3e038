#pragma once
// Dispatches over the upper triangle of an n x n grid of invocations (pairs (x, y) with x >= y),
// the shape of every pair kernel that visits all box pairs or all face pairs.

#include "gl/program.hpp"

#include <cstdint>

namespace glcollide::passes {

/// Dispatches `program` in tile x tile work groups over the n x n grid, in chunks of at most
/// 65535 groups per dimension, skipping chunks wholly below the diagonal; the shader adds
/// (u_tileOriginX, u_tileOriginY) to its invocation id and rejects invocations below the diagonal
/// itself. Ends with a shader-storage barrier.
void dispatchUpperTriangle(const gl::ComputeProgram& program, std::uint32_t n, std::uint32_t tile);

} // namespace glcollide::passes
