#pragma once
// KHR_debug helpers: a chaining debug-callback scope, object labels and debug groups.
// Internal to glcollide (includes epoxy); see platform.md §2.5 for the etiquette they follow.

#include <epoxy/gl.h>

#include <functional>
#include <memory>
#include <string_view>

namespace glcollide::gl {

/// One KHR_debug message; `text` is valid only during the handler call.
struct DebugMessage {
    GLenum source = 0;
    GLenum type = 0;
    GLuint id = 0;
    GLenum severity = 0;
    std::string_view text;
};

/// Installs a debug callback on the current context for its lifetime. It forwards every message
/// to `handler`, then to the callback that was installed before (the host's), with that
/// callback's user parameter, and puts the previous callback back on destruction.
/// Scopes may end in any order: one that ends while a later scope chains to it is unlinked from
/// that scope, which inherits its previous callback and enable states (a host callback installed
/// after a scope and chaining to it cannot be found, so a scope under one must outlive it).
/// The context must be current at construction and destruction. Not movable: GL holds a pointer to it.
class DebugOutputScope {
  public:
    using Handler = std::function<void(const DebugMessage&)>;

    enum Flags : unsigned {
        kNone = 0,
        kEnableOutput = 1u << 0, ///< glEnable(GL_DEBUG_OUTPUT) (off by default in non-debug contexts)
        kSynchronous = 1u << 1,  ///< glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS): callback on the calling thread
    };

    /// `flags` enable states are saved and restored on destruction.
    explicit DebugOutputScope(Handler handler, unsigned flags = kNone);
    ~DebugOutputScope();
    DebugOutputScope(const DebugOutputScope&) = delete;
    DebugOutputScope& operator=(const DebugOutputScope&) = delete;

    /// The callback that was installed before this scope (nullptr if none) and its user parameter.
    GLDEBUGPROC previousCallback() const { return m_previousCallback; }
    const void* previousUserParam() const { return m_previousUserParam; }

  private:
    static void GLAPIENTRY trampoline(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                      const GLchar* message, const void* userParam);

    Handler m_handler;
    unsigned m_flags = kNone;
    GLDEBUGPROC m_previousCallback = nullptr;
    const void* m_previousUserParam = nullptr;
    bool m_previousOutputEnabled = false;
    bool m_previousSynchronousEnabled = false;
};

/// glObjectLabel, with the label truncated to GL_MAX_LABEL_LENGTH - 1 characters.
/// `identifier` is GL_BUFFER, GL_PROGRAM, GL_QUERY, ...; `name` an existing object of that kind.
void labelObject(GLenum identifier, GLuint name, std::string_view label);

/// glPushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY) for its lifetime, so captures (RenderDoc,
/// apitrace) and debug output show which glcollide pass issued a call. Does nothing when the
/// group stack is full, rather than raising GL_STACK_OVERFLOW in the host's context.
class DebugGroup {
  public:
    explicit DebugGroup(std::string_view name, GLuint id = 0);
    ~DebugGroup();
    DebugGroup(const DebugGroup&) = delete;
    DebugGroup& operator=(const DebugGroup&) = delete;

  private:
    bool m_pushed = false;
};

} // namespace glcollide::gl
