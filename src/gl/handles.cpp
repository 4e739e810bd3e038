#include "gl/handles.hpp"

#include "gl/debug_output.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>

namespace glcollide::gl {

void deleteBuffer(GLname name) {
    glDeleteBuffers(1, &name);
}
void deleteProgram(GLname name) {
    glDeleteProgram(name);
}
void deleteQuery(GLname name) {
    glDeleteQueries(1, &name);
}

namespace {

// Every glcollide buffer is bound whole as a shader storage block, and a shader cannot address
// more than GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes of one (2^24 at least; llvmpipe 2^27). A
// larger buffer would allocate but be read wrongly: refuse it by name instead.
void checkStorageBlockSize(const std::string& label, std::size_t bytes) {
    constexpr std::size_t kGuaranteed = std::size_t{1} << 24; // GL 4.3's minimum: no query needed below
    if (bytes <= kGuaranteed) return;
    GLint64 limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
    if (limit > 0 && bytes > static_cast<std::uint64_t>(limit))
        throw Error("buffer '" + label + "' needs " + std::to_string(bytes) +
                    " bytes, more than this device's " + "GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " +
                    std::to_string(limit) +
                    " bytes (`glcollide info` shows it): use fewer or smaller bodies, or a device with a "
                    "larger limit");
}

} // namespace

Buffer::Buffer(std::string_view label, std::size_t bytes, const void* data) : m_bytes(bytes), m_label(label) {
    checkStorageBlockSize(m_label, bytes);
    GLuint name = 0;
    glGenBuffers(1, &name);
    m_handle = Handle<deleteBuffer>(name);
    glBindBuffer(GL_COPY_WRITE_BUFFER, name);
    // A zero-sized SSBO cannot be bound; keep a small placeholder so passes stay valid. The
    // placeholder may be larger than `data`: upload only the caller's `bytes` (found by ASan).
    const std::size_t allocated = std::max<std::size_t>(bytes, 16);
    const bool exact = allocated == bytes;
    glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(allocated), exact ? data : nullptr,
                 GL_DYNAMIC_COPY);
    if (!exact && data && bytes)
        glBufferSubData(GL_COPY_WRITE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw Error("GL out of memory allocating buffer '" + m_label + "' of " + std::to_string(bytes) +
                    " bytes");
    labelObject(GL_BUFFER, name, "glcollide/" + m_label);
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
    if (bytes == 0) return;
    glBindBuffer(GL_COPY_WRITE_BUFFER, name());
    glBufferSubData(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                    data);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void Buffer::fill32(std::uint32_t word) {
    if (bytes() == 0) return;
    glBindBuffer(GL_COPY_WRITE_BUFFER, name());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &word);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void Buffer::download(std::size_t offset, std::size_t bytes, void* out) const {
    if (bytes == 0) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, name());
    glGetBufferSubData(GL_COPY_READ_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                       out);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
}

void copyBufferData(const Buffer& source, const Buffer& target, std::size_t bytes, std::size_t targetOffset) {
    if (bytes == 0) return;
    if (bytes > source.bytes() || targetOffset > target.bytes() || bytes > target.bytes() - targetOffset)
        throw Error("copyBufferData: " + std::to_string(bytes) + " bytes from '" + source.label() + "' (" +
                    std::to_string(source.bytes()) + ") to '" + target.label() + "' (" +
                    std::to_string(target.bytes()) + ") at " + std::to_string(targetOffset));
    glBindBuffer(GL_COPY_READ_BUFFER, source.name());
    glBindBuffer(GL_COPY_WRITE_BUFFER, target.name());
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, static_cast<GLintptr>(targetOffset),
                        static_cast<GLsizeiptr>(bytes));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void Buffer::bindStorage(std::uint32_t binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, name());
}

} // namespace glcollide::gl
