#pragma once
// The engine's side of the GL state contract (docs/embedding.md, "GL state contract"): the host's bindings
// that a glcollide entry point may change are saved on entry and put back on exit. One guard per
// public Engine call, at the engine boundary; passes bind freely inside it.

#include "core/gpu_layout.hpp"

#include <array>
#include <cstdint>

namespace glcollide::gl {

/// Indexed GL_SHADER_STORAGE_BUFFER binding points glcollide's shaders use: 0 ...
/// GLC_BINDING_COUNT-1 of shaders/common/layout.glsl (tests/gl/layout_gl_test.cpp checks that no
/// kernel binds above).
inline constexpr std::uint32_t kStorageBindingCount = GLC_BINDING_COUNT;

/// Saves, on construction, the context state that glcollide's GL calls can change, and restores
/// it on destruction (also when an exception unwinds through it):
///  - Scope::Compute: the current program; the generic GL_SHADER_STORAGE_BUFFER binding and the
///    indexed bindings 0 .. kStorageBindingCount-1 (buffer, start, size); GL_DISPATCH_INDIRECT_BUFFER;
///    GL_COPY_READ_BUFFER and GL_COPY_WRITE_BUFFER; GL_QUERY_BUFFER where the context has it
///    (GL 4.4 / ARB_query_buffer_object), which is also unbound for the guard's lifetime, since a
///    bound query buffer would turn glGetQueryObject's result pointer into a buffer offset.
///  - Scope::Transfer (read-backs, uploads): GL_COPY_READ_BUFFER and GL_COPY_WRITE_BUFFER only.
///  - Scope::Teardown: as Compute, but a saved buffer name that no longer names an object (the host
///    had bound one of the buffers being deleted; GL already reset that binding to 0) is not
///    rebound, since binding a deleted name is an error in a core context.
/// In every scope, a current program the host had already deleted (GL keeps a deleted program
/// alive only while it is current) is gone once the engine's program replaced it: 0 is restored.
/// Never touched by glcollide, so not saved: vertex array, GL_ARRAY_BUFFER, GL_ELEMENT_ARRAY_BUFFER
/// (it lives in the VAO), uniform / atomic-counter / pixel buffers, textures, framebuffers,
/// capabilities, active queries (glcollide uses glQueryCounter only, which starts nothing).
///
/// Cost (Compute): 3 + 1 + kStorageBindingCount glGetInteger calls, two more per non-zero indexed
/// binding, the same number of binds and one glIsProgram on restore: 0.3-0.7 us on llvmpipe
/// (HostContextGl.GuardCost prints it).
/// Needs the context current at both ends; not copyable or movable.
class HostStateGuard {
  public:
    enum class Scope { Compute, Transfer, Teardown };

    /// What the context offers beyond GL 4.3; probed once (at engine construction).
    struct Features {
        bool queryBuffer = false; ///< GL_QUERY_BUFFER exists (GL >= 4.4 or ARB_query_buffer_object)
    };
    /// Needs a current context.
    [[nodiscard]] static Features probe();

    HostStateGuard(Scope scope, Features features);
    ~HostStateGuard();
    HostStateGuard(const HostStateGuard&) = delete;
    HostStateGuard& operator=(const HostStateGuard&) = delete;

  private:
    struct Indexed {
        std::uint32_t buffer = 0;
        std::int64_t start = 0;
        std::int64_t size = 0;
    };

    Scope m_scope;
    Features m_features;
    std::uint32_t m_copyRead = 0, m_copyWrite = 0;
    std::uint32_t m_program = 0, m_storage = 0, m_dispatchIndirect = 0, m_queryBuffer = 0;
    std::array<Indexed, kStorageBindingCount> m_indexed{};
};

} // namespace glcollide::gl
