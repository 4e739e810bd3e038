#pragma once
// Move-only owners of GL objects. They hold plain GLuint names (std::uint32_t) so this header
// needs no GL loader; the .cpp uses epoxy. A handle deletes its object on destruction, which
// requires the owning context (or one sharing with it) to be current.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>
#include <string_view>
#include <utility>

namespace glcollide::gl {

using GLname = std::uint32_t;

/// Common move-only ownership of one GL name.
template <void (*Delete)(GLname)> class Handle {
  public:
    Handle() = default;
    explicit Handle(GLname name) : m_name(name) {}
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : m_name(std::exchange(other.m_name, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            m_name = std::exchange(other.m_name, 0);
        }
        return *this;
    }
    [[nodiscard]] GLname name() const { return m_name; }
    explicit operator bool() const { return m_name != 0; }
    void reset() {
        if (m_name != 0) Delete(m_name);
        m_name = 0;
    }

  private:
    GLname m_name = 0;
};

void deleteBuffer(GLname name);
void deleteProgram(GLname name);
void deleteQuery(GLname name);

/// A GL buffer object of fixed byte size, labelled for debuggers (KHR_debug).
class Buffer {
  public:
    Buffer() = default;
    /// Allocates `bytes` (0 allowed: a 16-byte placeholder is made, so binding stays valid) and
    /// uploads `data` if not null. `label` appears in RenderDoc/apitrace as "glcollide/<label>".
    Buffer(std::string_view label, std::size_t bytes, const void* data = nullptr);

    [[nodiscard]] GLname name() const { return m_handle.name(); }
    [[nodiscard]] std::size_t bytes() const { return m_bytes; }
    [[nodiscard]] const std::string& label() const { return m_label; }
    explicit operator bool() const { return static_cast<bool>(m_handle); }

    void upload(std::size_t offset, std::size_t bytes, const void* data);
    /// Sets every 32-bit word of the buffer to `word` on the GPU (glClearBufferData, GL 4.3).
    void fill32(std::uint32_t word);
    /// Reads back after a GL_BUFFER_UPDATE_BARRIER_BIT barrier (issued here).
    void download(std::size_t offset, std::size_t bytes, void* out) const;
    /// glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, this).
    void bindStorage(std::uint32_t binding) const;

  private:
    Handle<deleteBuffer> m_handle;
    std::size_t m_bytes = 0;
    std::string m_label;
};

/// Copies the first `bytes` of `source` into `target` at byte `targetOffset` on the GPU
/// (glCopyBufferSubData).
void copyBufferData(const Buffer& source, const Buffer& target, std::size_t bytes,
                    std::size_t targetOffset = 0);

/// A buffer holding a copy of `data` (a placeholder when empty).
template <typename T> Buffer makeBuffer(std::string_view label, const std::vector<T>& data) {
    return Buffer(label, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

} // namespace glcollide::gl
