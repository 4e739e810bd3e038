#pragma once
// Offscreen snapshots of a simulation, drawn from the engine's own GPU buffers: the position buffer
// is the vertex buffer and the face buffer the index buffer of the renderer's vertex array, so
// nothing is read back to draw. Used by `glcollide render`; the renderer saves and restores every
// piece of GL state it touches, so it can also run inside a host's context.

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace glcollide::render {

/// An 8-bit RGBA image, rows from top to bottom.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; ///< width * height * 4 bytes

    /// The pixel at column x (0 = left), row y (0 = top).
    [[nodiscard]] std::array<std::uint8_t, 4> pixel(int x, int y) const;
};

struct RenderOptions {
    int width = 800;  ///< pixels, 1 ... GL_MAX_RENDERBUFFER_SIZE
    int height = 600; ///< pixels, 1 ... GL_MAX_RENDERBUFFER_SIZE
    int samples = 4;  ///< multisampling; clamped to GL_MAX_SAMPLES; 0 or 1 = none
    /// Smooth shading from per-vertex normals (area-weighted, gathered on the GPU each frame);
    /// false: flat, one normal per face.
    bool smooth = true;
};

/// What a frame is seen from: a perspective camera plus its matrices (OpenGL clip conventions).
struct View {
    glm::dvec3 eye{0.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovDeg = 45.0;    ///< vertical field of view
    double nearPlane = 0.01; ///< m
    double farPlane = 100.0; ///< m
    glm::dmat4 viewMatrix{1.0};
    glm::dmat4 projection{1.0};

    [[nodiscard]] glm::dmat4 viewProjection() const { return projection * viewMatrix; }
    /// Where a world point lands in an image of this size: x from the left, y from the top, in
    /// pixels (pixel centres at +0.5); z is the NDC depth. Points behind the eye give w <= 0: the
    /// result is then meaningless (check with inFront()).
    [[nodiscard]] glm::dvec3 project(const glm::dvec3& world, int width, int height) const;
    [[nodiscard]] bool inFront(const glm::dvec3& world) const;
};

/// The ground grid: a square in the plane y = centre.y.
struct Grid {
    glm::dvec3 centre{0.0};
    double halfSize = 1.0; ///< m
    double spacing = 0.1;  ///< m between minor lines (a 1, 2 or 5 times a power of ten); major every 5
};

/// The view of a scene: its CameraSettings when it has them, else a fixed 3/4 view from above and
/// in front (+z, turned 35° towards +x, 25° up) at the distance where the initial bounding box of
/// all bodies (down to the ground plane when the ground effect is on) fills the image with a
/// margin. `aspect` = width / height.
View sceneView(const Scene& scene, double aspect);

/// A perspective view from `eye` towards `target` with its matrices; `aspect` = width / height.
View lookAtView(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double fovDeg,
                double nearPlane, double farPlane, double aspect);

/// Where SceneRenderer::draw draws: a framebuffer (0: the window's own) and the viewport's size,
/// from its lower left corner.
struct DrawTarget {
    std::uint32_t framebuffer = 0;
    int width = 0;
    int height = 0;
};

/// What SceneRenderer::draw adds over the shaded surfaces (`glcollide view`'s toggles).
struct Overlays {
    bool wireframe = false;   ///< every face's edges, dark
    bool pinnedNodes = false; ///< nodes with inverse mass 0 as points
    /// A segment between two world points (the viewer's pull: from the node to the cursor).
    std::optional<std::array<glm::dvec3, 2>> segment;
    /// Segments drawn in one colour (the viewer's candidate face pairs: centroid to centroid).
    std::vector<std::array<glm::vec3, 2>> pairLines;
    /// Segments in a second colour (the viewer's feature contacts: closest point to closest point).
    std::vector<std::array<glm::vec3, 2>> contactLines;
    /// Segments in a third colour, drawn first (the viewer's broad-phase boxes: their 12 edges each).
    std::vector<std::array<glm::vec3, 2>> boxLines;
};

/// The grid under a scene: at the ground height when the ground effect is on, else just below the
/// lowest initial node; centred under the initial bounding box and a few times its size.
Grid sceneGrid(const Scene& scene);

/// Draws an engine's current state into its own framebuffer and reads the pixels back.
/// Needs the engine's GL context current for all calls, the destructor included.
class SceneRenderer {
  public:
    /// Builds the programs, vertex array, framebuffers and the per-face object table of `engine`
    /// (which must outlive no call: every call takes it again). Throws Error for bad sizes, shader
    /// errors or an incomplete framebuffer.
    SceneRenderer(const Engine& engine, const RenderOptions& options = {});
    ~SceneRenderer();
    SceneRenderer(SceneRenderer&&) noexcept;
    SceneRenderer& operator=(SceneRenderer&&) noexcept;

    /// Renders the engine's current positions; faces in engine.readIntersectingPairs() (the last
    /// substep's, or the last detectCollisions()'s) are highlighted. Restores the GL state.
    Image renderFrame(const Engine& engine);
    /// Renders with the faces of these global face pairs highlighted (indices >= faceCount are
    /// ignored). Restores the GL state.
    Image renderFrame(const Engine& engine, std::span<const std::array<std::uint32_t, 2>> highlightedPairs);

    /// Draws the engine's current positions into `target` (cleared first) with these faces
    /// highlighted and the overlays; no readback. Restores the GL state. The view is the last
    /// setView()'s (at first the scene's, sceneView()).
    void draw(const Engine& engine, std::span<const std::array<std::uint32_t, 2>> highlightedPairs,
              const DrawTarget& target, const Overlays& overlays = {});
    /// The view the next frames are drawn from; the lights turn with it (they are fixed relative
    /// to the camera). The grid and the shadow map's square stay the scene's.
    void setView(const View& view);
    /// Smooth (per-vertex normals) or flat shading from the next frame on.
    void setSmooth(bool smooth);

    [[nodiscard]] const View& view() const;
    [[nodiscard]] const Grid& grid() const;
    [[nodiscard]] int width() const;
    [[nodiscard]] int height() const;
    [[nodiscard]] int samples() const; ///< after clamping; 0 = no multisampling
    /// Faces drawn highlighted in the last frame.
    [[nodiscard]] std::size_t highlightedFaces() const;

    /// Colour of body `index` (a palette of 10 without red, repeating), before shading, in [0, 1].
    static glm::vec3 bodyColour(std::size_t index);
    /// Colour of intersecting faces (red), before shading.
    static glm::vec3 highlightColour();
    /// What the back side of a face (winding clockwise as seen) is tinted towards, halfway.
    static glm::vec3 backTint();
    /// Colour of Overlays::pairLines.
    static glm::vec3 pairLineColour();
    /// Colours of Overlays::contactLines and Overlays::boxLines.
    static glm::vec3 contactLineColour();
    static glm::vec3 boxLineColour();
    /// Colour where nothing is drawn.
    static glm::vec3 backgroundColour();

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// Reads the bound GL_READ_FRAMEBUFFER's read buffer (lower left width x height) into an image,
/// rows turned top to bottom. Changes the pixel-pack state (the caller saves it if it must).
Image readPixels(int width, int height);

/// Writes an image as an 8-bit RGB PNG (alpha dropped: frames are opaque). Throws Error naming the
/// path when it cannot be written.
void writePng(const std::filesystem::path& path, const Image& image);

} // namespace glcollide::render
