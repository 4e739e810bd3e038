#pragma once
// The SSBOs the passes read and write. A buffer a scene's effects do not need stays empty
// (never allocated); a pass binds only what it uses and checks it is there.

#include "gl/handles.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::passes {

/// The engine's own buffers, in declaration order of DeviceBuffers (the plan lists the ones a
/// scene needs by id; the engine allocates exactly those).
enum class BufferId : std::uint8_t {
    Positions,
    Velocities,
    Faces,
    Forces,
    Springs,
    NodeSpringOffsets,
    NodeSpringList,
    HeavyNodes,
    NodeFaceOffsets,
    NodeFaceList,
    ContactForces,
    Health,
    PredictedPositions
};
inline constexpr std::size_t kBufferIdCount = 13;

/// The buffer's label: its GL object label and its name in `run`'s output and --stats.
const char* bufferLabel(BufferId id);

struct DeviceBuffers {
    std::uint32_t nodeCount = 0;
    std::uint32_t faceCount = 0;
    std::uint32_t springCount = 0;

    gl::Buffer positions;         ///< vec4: xyz m, w inverse mass
    gl::Buffer velocities;        ///< vec4: xyz m/s
    gl::Buffer faces;             ///< uint[3 * faceCount]
    gl::Buffer forces;            ///< vec4: xyz N (NodeForce or SpringUpdate)
    gl::Buffer springs;           ///< GpuSpring (SpringUpdate)
    gl::Buffer nodeSpringOffsets; ///< uint[nodeCount + 1] (SpringUpdate)
    gl::Buffer nodeSpringList;    ///< uint[2 * springCount] (SpringUpdate)
    gl::Buffer heavyNodes; ///< uint[]: nodes with more than kHeavyRow springs (SpringUpdate, ImplicitSolve)
    gl::Buffer nodeFaceOffsets; ///< uint[nodeCount + 1] (NodeForce with wind)
    gl::Buffer nodeFaceList;    ///< uint[3 * faceCount] (NodeForce with wind)
    gl::Buffer contactForces;   ///< ivec4 fixed point (collisions: ContactResponse → NodeUpdate)
    gl::Buffer health;          ///< GpuHealth (NodeUpdate with EngineOptions::checkFinite)
    /// vec4: x1, the end of the substep as the integrator predicts it (NodePredict; continuous
    /// detection reads [positions, predictedPositions])
    gl::Buffer predictedPositions;

    /// The buffer `id` names.
    [[nodiscard]] gl::Buffer& operator[](BufferId id);
    [[nodiscard]] const gl::Buffer& operator[](BufferId id) const;

    /// Labels of the allocated buffers, in declaration order.
    [[nodiscard]] std::vector<std::string> allocatedLabels() const;
    /// Sum of allocated bytes.
    [[nodiscard]] std::size_t allocatedBytes() const;
};

/// Binds `buffer` at `binding`; throws Error naming `pass` and `what` if it was never allocated
/// (a pass composed without the effect that allocates its input is an engine bug).
void bindRequired(const gl::Buffer& buffer, std::uint32_t binding, const char* pass, const char* what);

} // namespace glcollide::passes
