#include "gl/debug_output.hpp"

#include <algorithm>

namespace glcollide::gl {

DebugOutputScope::DebugOutputScope(Handler handler, unsigned flags)
    : m_handler(std::move(handler)), m_flags(flags) {
    // One callback slot per context: remember the host's so we can chain to it and restore it.
    void* previous = nullptr;
    void* previousParam = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &previous);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &previousParam);
    m_previousCallback = reinterpret_cast<GLDEBUGPROC>(previous);
    m_previousUserParam = previousParam;
    m_previousOutputEnabled = glIsEnabled(GL_DEBUG_OUTPUT) == GL_TRUE;
    m_previousSynchronousEnabled = glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS) == GL_TRUE;
    glDebugMessageCallback(&DebugOutputScope::trampoline, this);
    if (m_flags & kEnableOutput) glEnable(GL_DEBUG_OUTPUT);
    if (m_flags & kSynchronous) glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
}

DebugOutputScope::~DebugOutputScope() {
    void* current = nullptr;
    void* currentParam = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &current);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &currentParam);
    // Out of order (an engine destroyed before one created after it): a later scope chains to us.
    // Scopes above us in the slot are found through the slot itself (our trampoline's user
    // parameter is always a scope), so unlinking needs no registry: the later scope takes over our
    // previous callback and the enable states we would have restored.
    GLDEBUGPROC callback = reinterpret_cast<GLDEBUGPROC>(current);
    const void* param = currentParam;
    while (callback == &DebugOutputScope::trampoline && param != nullptr && param != this) {
        auto* later = const_cast<DebugOutputScope*>(static_cast<const DebugOutputScope*>(param));
        if (later->m_previousCallback == &DebugOutputScope::trampoline &&
            later->m_previousUserParam == this) {
            later->m_previousCallback = m_previousCallback;
            later->m_previousUserParam = m_previousUserParam;
            if (m_flags & kEnableOutput) {
                later->m_flags |= kEnableOutput;
                later->m_previousOutputEnabled = m_previousOutputEnabled;
            }
            if (m_flags & kSynchronous) {
                later->m_flags |= kSynchronous;
                later->m_previousSynchronousEnabled = m_previousSynchronousEnabled;
            }
            return;
        }
        callback = later->m_previousCallback;
        param = later->m_previousUserParam;
    }
    if ((m_flags & kSynchronous) && !m_previousSynchronousEnabled) glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    if ((m_flags & kEnableOutput) && !m_previousOutputEnabled) glDisable(GL_DEBUG_OUTPUT);
    // Restore only if the slot still holds us: if someone else replaced it meanwhile, overwriting
    // theirs would be worse than leaving it.
    if (reinterpret_cast<GLDEBUGPROC>(current) == &DebugOutputScope::trampoline && currentParam == this)
        glDebugMessageCallback(m_previousCallback, m_previousUserParam);
}

void GLAPIENTRY DebugOutputScope::trampoline(GLenum source, GLenum type, GLuint id, GLenum severity,
                                             GLsizei length, const GLchar* message, const void* userParam) {
    const auto* self = static_cast<const DebugOutputScope*>(userParam);
    if (self == nullptr) return;
    // length < 0 means NUL-terminated (allowed by the spec for callbacks from some drivers).
    const std::string_view text = message == nullptr ? std::string_view()
                                  : length < 0       ? std::string_view(message)
                                               : std::string_view(message, static_cast<std::size_t>(length));
    if (self->m_handler) {
        // The callback is called from inside the driver: exceptions must not cross it.
        try {
            self->m_handler(DebugMessage{source, type, id, severity, text});
        } catch (...) {
        }
    }
    if (self->m_previousCallback != nullptr)
        self->m_previousCallback(source, type, id, severity, length, message, self->m_previousUserParam);
}

void labelObject(GLenum identifier, GLuint name, std::string_view label) {
    GLint maxLength = 0;
    glGetIntegerv(GL_MAX_LABEL_LENGTH, &maxLength);
    if (maxLength <= 1) return;
    // The limit counts the terminator: a label of MAX_LABEL_LENGTH characters is GL_INVALID_VALUE.
    const std::size_t length = std::min(label.size(), static_cast<std::size_t>(maxLength - 1));
    glObjectLabel(identifier, name, static_cast<GLsizei>(length), label.data());
}

DebugGroup::DebugGroup(std::string_view name, GLuint id) {
    GLint depth = 0, maxDepth = 0, maxMessage = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depth);
    glGetIntegerv(GL_MAX_DEBUG_GROUP_STACK_DEPTH, &maxDepth);
    glGetIntegerv(GL_MAX_DEBUG_MESSAGE_LENGTH, &maxMessage);
    if (depth >= maxDepth || maxMessage <= 1) return;
    const std::size_t length = std::min(name.size(), static_cast<std::size_t>(maxMessage - 1));
    glPushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, id, static_cast<GLsizei>(length), name.data());
    m_pushed = true;
}

DebugGroup::~DebugGroup() {
    if (m_pushed) glPopDebugGroup();
}

} // namespace glcollide::gl
