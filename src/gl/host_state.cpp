#include "gl/host_state.hpp"

#include "core/gpu_layout.hpp"

#include <epoxy/gl.h>

namespace glcollide::gl {

namespace {

std::uint32_t getName(GLenum binding) {
    GLint value = 0;
    glGetIntegerv(binding, &value);
    return static_cast<std::uint32_t>(value);
}

} // namespace

HostStateGuard::Features HostStateGuard::probe() {
    Features f;
    f.queryBuffer = epoxy_gl_version() >= 44 || epoxy_has_gl_extension("GL_ARB_query_buffer_object");
    return f;
}

HostStateGuard::HostStateGuard(Scope scope, Features features) : m_scope(scope), m_features(features) {
    m_copyRead = getName(GL_COPY_READ_BUFFER_BINDING);
    m_copyWrite = getName(GL_COPY_WRITE_BUFFER_BINDING);
    if (m_scope == Scope::Transfer) return;
    m_program = getName(GL_CURRENT_PROGRAM);
    m_storage = getName(GL_SHADER_STORAGE_BUFFER_BINDING);
    m_dispatchIndirect = getName(GL_DISPATCH_INDIRECT_BUFFER_BINDING);
    for (GLuint i = 0; i < kStorageBindingCount; ++i) {
        Indexed& b = m_indexed[i];
        GLint name = 0;
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &name);
        b.buffer = static_cast<std::uint32_t>(name);
        // Start and size mean nothing without a buffer: skip two queries in the common case.
        if (b.buffer == 0) continue;
        GLint64 start = 0, size = 0;
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &start);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &size);
        b.start = start;
        b.size = size;
    }
    if (m_features.queryBuffer) {
        m_queryBuffer = getName(GL_QUERY_BUFFER_BINDING);
        if (m_queryBuffer != 0) glBindBuffer(GL_QUERY_BUFFER, 0);
    }
}

HostStateGuard::~HostStateGuard() {
    // In Teardown, a name the host had bound may have been one of the objects just deleted: GL
    // has reset that binding to 0 already, and rebinding the dead name would be an error.
    const bool teardown = m_scope == Scope::Teardown;
    const auto buffer = [&](std::uint32_t name) -> GLuint {
        return name != 0 && teardown && !glIsBuffer(name) ? 0u : name;
    };
    if (m_scope != Scope::Transfer) {
        for (GLuint i = 0; i < kStorageBindingCount; ++i) {
            const Indexed& b = m_indexed[i];
            const GLuint name = buffer(b.buffer);
            // A range has a positive size, so a size <= 0 means the host used glBindBufferBase
            // (reported as 0 by the spec, as -1 by some drivers; it follows the buffer's size).
            if (name == 0 || b.size <= 0 || b.start < 0)
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, name);
            else
                glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, name, static_cast<GLintptr>(b.start),
                                  static_cast<GLsizeiptr>(b.size));
        }
        // glBindBufferBase/Range also set the generic binding: restore it after them.
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer(m_storage));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, buffer(m_dispatchIndirect));
        if (m_features.queryBuffer) glBindBuffer(GL_QUERY_BUFFER, buffer(m_queryBuffer));
        // A program the host deleted while it was current lives on only as long as it stays
        // current; once ours replaced it GL deleted it, and 0 is all that can be restored.
        glUseProgram(m_program != 0 && !glIsProgram(m_program) ? 0u : m_program);
    }
    glBindBuffer(GL_COPY_READ_BUFFER, buffer(m_copyRead));
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffer(m_copyWrite));
}

} // namespace glcollide::gl
