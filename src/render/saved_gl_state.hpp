#pragma once
// Everything the renderer changes in a context, captured on construction and put back on
// destruction, so rendering inside a host's context leaves it as it was
// (docs/design/decisions/0016-host-gl-state-contract.md: a host that embeds glcollide sees no surprise
// changes to its GL state).

#include <epoxy/gl.h>

#include <array>

namespace glcollide::render {

class SavedGlState {
  public:
    /// Saves the state listed in the .cpp, including the indexed shader-storage bindings
    /// 0 ... kStorageBindings - 1 and the 2D texture and sampler bound on texture unit
    /// `textureUnit` (0-based).
    explicit SavedGlState(GLuint textureUnit);
    /// The indexed shader-storage bindings the renderer uses (render/surface.vert, surface.frag).
    static constexpr GLuint kStorageBindings = 5;
    ~SavedGlState();
    SavedGlState(const SavedGlState&) = delete;
    SavedGlState& operator=(const SavedGlState&) = delete;

  private:
    struct Capability {
        GLenum cap;
        GLboolean enabled;
    };

    struct StorageBinding {
        GLint buffer = 0;
        GLint64 start = 0, size = 0;
    };
    GLuint m_textureUnit;
    GLint m_drawFramebuffer = 0, m_readFramebuffer = 0, m_renderbuffer = 0;
    std::array<GLint, 4> m_viewport{};
    GLint m_program = 0, m_vertexArray = 0;
    GLint m_arrayBuffer = 0, m_copyReadBuffer = 0, m_copyWriteBuffer = 0, m_storageBuffer = 0,
          m_pixelPackBuffer = 0;
    std::array<StorageBinding, kStorageBindings> m_storage{};
    GLint m_activeTexture = 0, m_texture2D = 0, m_sampler = 0;
    GLint m_packAlignment = 4, m_packRowLength = 0, m_packSkipRows = 0, m_packSkipPixels = 0;
    std::array<Capability, 15> m_caps{};
    GLint m_depthFunc = GL_LESS, m_frontFace = GL_CCW;
    GLboolean m_depthMask = GL_TRUE;
    std::array<GLboolean, 4> m_colorMask{};
    std::array<GLfloat, 4> m_clearColor{};
    GLdouble m_clearDepth = 1.0;
    GLfloat m_polygonOffsetFactor = 0.0f, m_polygonOffsetUnits = 0.0f;
    std::array<GLint, 2> m_polygonMode{GL_FILL, GL_FILL};
};

} // namespace glcollide::render
