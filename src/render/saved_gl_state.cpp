#include "render/saved_gl_state.hpp"

namespace glcollide::render {
namespace {

// Capabilities the renderer sets one way or the other while drawing.
constexpr std::array<GLenum, 15> kCapabilities = {
    GL_DEPTH_TEST,
    GL_CULL_FACE,
    GL_BLEND,
    GL_SCISSOR_TEST,
    GL_STENCIL_TEST,
    GL_POLYGON_OFFSET_FILL,
    GL_POLYGON_OFFSET_LINE, // the viewer's wireframe overlay
    GL_MULTISAMPLE,
    GL_FRAMEBUFFER_SRGB,
    GL_RASTERIZER_DISCARD,
    GL_SAMPLE_ALPHA_TO_COVERAGE,
    GL_PRIMITIVE_RESTART,
    GL_DEPTH_CLAMP,
    GL_DITHER,
    GL_PROGRAM_POINT_SIZE, // the viewer's pinned-node overlay sets its point size in the shader
};

} // namespace

SavedGlState::SavedGlState(GLuint textureUnit) : m_textureUnit(textureUnit) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &m_drawFramebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &m_readFramebuffer);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &m_renderbuffer);
    glGetIntegerv(GL_VIEWPORT, m_viewport.data());
    glGetIntegerv(GL_CURRENT_PROGRAM, &m_program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &m_vertexArray);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &m_arrayBuffer);
    glGetIntegerv(GL_COPY_READ_BUFFER_BINDING, &m_copyReadBuffer);
    glGetIntegerv(GL_COPY_WRITE_BUFFER_BINDING, &m_copyWriteBuffer);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &m_storageBuffer);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &m_pixelPackBuffer);
    for (GLuint i = 0; i < kStorageBindings; ++i) {
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &m_storage[i].buffer);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &m_storage[i].start);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &m_storage[i].size);
    }
    glGetIntegerv(GL_FRONT_FACE, &m_frontFace);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &m_activeTexture);
    glActiveTexture(GL_TEXTURE0 + textureUnit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &m_texture2D);
    glGetIntegerv(GL_SAMPLER_BINDING, &m_sampler);
    glActiveTexture(static_cast<GLenum>(m_activeTexture));
    glGetIntegerv(GL_PACK_ALIGNMENT, &m_packAlignment);
    glGetIntegerv(GL_PACK_ROW_LENGTH, &m_packRowLength);
    glGetIntegerv(GL_PACK_SKIP_ROWS, &m_packSkipRows);
    glGetIntegerv(GL_PACK_SKIP_PIXELS, &m_packSkipPixels);
    for (std::size_t i = 0; i < kCapabilities.size(); ++i)
        m_caps[i] = {kCapabilities[i], glIsEnabled(kCapabilities[i])};
    glGetIntegerv(GL_DEPTH_FUNC, &m_depthFunc);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &m_depthMask);
    glGetBooleanv(GL_COLOR_WRITEMASK, m_colorMask.data());
    glGetFloatv(GL_COLOR_CLEAR_VALUE, m_clearColor.data());
    glGetDoublev(GL_DEPTH_CLEAR_VALUE, &m_clearDepth);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &m_polygonOffsetFactor);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &m_polygonOffsetUnits);
    glGetIntegerv(GL_POLYGON_MODE, m_polygonMode.data());
}

SavedGlState::~SavedGlState() {
    glFrontFace(static_cast<GLenum>(m_frontFace));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(m_drawFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(m_readFramebuffer));
    glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(m_renderbuffer));
    glViewport(m_viewport[0], m_viewport[1], m_viewport[2], m_viewport[3]);
    // A program deleted while current lives on only as long as it stays current: once the renderer
    // switched away it is gone, and the host would have had no program bound either.
    const auto program = static_cast<GLuint>(m_program);
    glUseProgram(program != 0 && glIsProgram(program) ? program : 0);
    glBindVertexArray(static_cast<GLuint>(m_vertexArray));
    // Indexed bindings also set the generic binding point: restore them first.
    for (GLuint i = 0; i < kStorageBindings; ++i) {
        const StorageBinding& b = m_storage[i];
        const auto buffer = static_cast<GLuint>(b.buffer);
        if (buffer != 0 && b.size > 0)
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, buffer, static_cast<GLintptr>(b.start),
                              static_cast<GLsizeiptr>(b.size));
        else
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buffer);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(m_storageBuffer));
    glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(m_arrayBuffer));
    glBindBuffer(GL_COPY_READ_BUFFER, static_cast<GLuint>(m_copyReadBuffer));
    glBindBuffer(GL_COPY_WRITE_BUFFER, static_cast<GLuint>(m_copyWriteBuffer));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(m_pixelPackBuffer));
    glActiveTexture(GL_TEXTURE0 + m_textureUnit);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(m_texture2D));
    glBindSampler(m_textureUnit, static_cast<GLuint>(m_sampler));
    glActiveTexture(static_cast<GLenum>(m_activeTexture));
    glPixelStorei(GL_PACK_ALIGNMENT, m_packAlignment);
    glPixelStorei(GL_PACK_ROW_LENGTH, m_packRowLength);
    glPixelStorei(GL_PACK_SKIP_ROWS, m_packSkipRows);
    glPixelStorei(GL_PACK_SKIP_PIXELS, m_packSkipPixels);
    for (const Capability& c : m_caps) {
        if (c.enabled)
            glEnable(c.cap);
        else
            glDisable(c.cap);
    }
    glDepthFunc(static_cast<GLenum>(m_depthFunc));
    glDepthMask(m_depthMask);
    glColorMask(m_colorMask[0], m_colorMask[1], m_colorMask[2], m_colorMask[3]);
    glClearColor(m_clearColor[0], m_clearColor[1], m_clearColor[2], m_clearColor[3]);
    glClearDepth(m_clearDepth);
    glPolygonOffset(m_polygonOffsetFactor, m_polygonOffsetUnits);
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(m_polygonMode[0]));
}

} // namespace glcollide::render
