// The offscreen renderer (src/render): a reference image, an independent check of where each body
// lands (the camera matrix applied on the CPU), highlighted intersecting faces, the view from the
// scene file, PNG output, and the GL state it must leave as it found it.

#include "render/scene_renderer.hpp"
#include "support/gl_test_environment.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

namespace glcollide {
namespace {

using render::Image;
using render::SceneRenderer;

const std::filesystem::path kImages = std::filesystem::path(GLCOLLIDE_TEST_DATA_DIR) / "images";

/// Two 0.4 m tet boxes standing on the ground, the second turned 30° about y. `gapX` is the x
/// distance between their centres: 0.7 leaves them apart, 0.25 makes them overlap.
Scene twoBoxes(double gapX, bool collisions) {
    const std::string box =
        R"("generator": {"type": "tet_box", "size": [0.4, 0.4, 0.4], "resolution": [2, 2, 2]},
                                "mass": 1)";
    const std::string json = R"({"format_version": 1, "name": "two boxes",
      "effects": ["ground")" +
                             std::string(collisions ? R"(, "collisions")" : "") + R"(],
      "objects": [
        {"name": "left", )" + box +
                             R"(, "transform": {"translate": [-0.35, 0.2, 0]}},
        {"name": "right", )" +
                             box + R"(, "transform": {"translate": [)" + std::to_string(gapX - 0.35) +
                             R"(, 0.2, 0.05], "rotate_deg": [0, 30, 0]}}
      ]})";
    return parseScene(json, ".", "render test");
}

struct Loaded {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
};

Loaded loadPng(const std::filesystem::path& path) {
    Loaded out;
    int channels = 0;
    stbi_uc* data = stbi_load(path.string().c_str(), &out.width, &out.height, &channels, 3);
    if (data == nullptr) return out;
    out.rgb.assign(data,
                   data + static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 3);
    stbi_image_free(data);
    return out;
}

/// Hue in degrees [0, 360) of an RGB colour in [0, 1]; -1 for a grey.
double hue(double r, double g, double b) {
    const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), c = mx - mn;
    if (c < 1e-6) return -1.0;
    double h = 0.0;
    if (mx == r)
        h = std::fmod((g - b) / c + 6.0, 6.0);
    else if (mx == g)
        h = (b - r) / c + 2.0;
    else
        h = (r - g) / c + 4.0;
    return 60.0 * h;
}

double hueDistance(double a, double b) {
    const double d = std::abs(a - b);
    return std::min(d, 360.0 - d);
}

double pixelHue(const Image& image, int x, int y) {
    const auto p = image.pixel(x, y);
    return hue(p[0] / 255.0, p[1] / 255.0, p[2] / 255.0);
}

/// Pixels in the highlight colour (red, shaded): red clearly dominant over green and blue.
/// No palette colour passes (the reddest, orange, has green at 0.59 of red).
std::size_t highlightPixels(const Image& image) {
    std::size_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto p = image.pixel(x, y);
            if (p[0] > 90 && p[1] < 0.4 * p[0] && p[2] < 0.4 * p[0]) ++n;
        }
    return n;
}

glm::dvec3 centroid(const Body& body) {
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : body.positions) c += p;
    return c / static_cast<double>(body.positions.size());
}

TEST(RenderGl, MatchesTheReferenceImage) {
    Engine engine(twoBoxes(0.7, false));
    SceneRenderer renderer(engine, {160, 120, 4});
    const Image image = renderer.renderFrame(engine);
    ASSERT_EQ(image.rgba.size(), 160u * 120u * 4u);
    const std::filesystem::path reference = kImages / "two_boxes_160x120.png";
    if (std::getenv("GLCOLLIDE_UPDATE_REFERENCE_IMAGES") != nullptr) {
        render::writePng(reference, image);
        GTEST_SKIP() << "wrote " << reference;
    }
    const Loaded ref = loadPng(reference);
    ASSERT_EQ(ref.width, 160) << reference << " (regenerate with GLCOLLIDE_UPDATE_REFERENCE_IMAGES=1)";
    ASSERT_EQ(ref.height, 120);
    // The reference was rendered on llvmpipe (Mesa 22.3.6), where this test reproduces it exactly.
    // Other rasterisers differ at triangle edges and silhouettes (coverage rules along shared edges,
    // MSAA sample positions and resolve), at shadow borders (shadow-map depth precision, PCF
    // comparisons) and by a rounding step or two in smooth shading. Hence: a pixel counts as
    // different only beyond 8/255 in some channel, and at most 1 % of the pixels (192, about the
    // number of silhouette pixels here) may differ.
    std::size_t differing = 0;
    for (std::size_t i = 0, n = 160u * 120u; i < n; ++i) {
        int worst = 0;
        for (std::size_t c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(image.rgba[4 * i + c]) - int(ref.rgb[3 * i + c])));
        if (worst > 8) ++differing;
    }
    if (differing > 160u * 120u / 100u) {
        const std::filesystem::path actual =
            std::filesystem::path(::testing::TempDir()) / "two_boxes_160x120_actual.png";
        render::writePng(actual, image);
        ADD_FAILURE() << differing << " pixels differ by more than 8/255 from " << reference
                      << "; this run: " << actual;
    }
}

TEST(RenderGl, EachBodyIsWhereTheCameraMatrixPutsIt) {
    const Scene scene = twoBoxes(0.7, false);
    Engine engine(scene);
    SceneRenderer renderer(engine, {160, 120, 4});
    const Image image = renderer.renderFrame(engine);
    const render::View& view = renderer.view();
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        // The box centre is inside the box; the front face covers it on screen.
        const glm::dvec3 p = view.project(centroid(scene.bodies[b]), image.width, image.height);
        const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
        ASSERT_TRUE(x >= 0 && x < image.width && y >= 0 && y < image.height)
            << "body " << b << " at " << x << "," << y;
        const glm::vec3 own = SceneRenderer::bodyColour(b), other = SceneRenderer::bodyColour(1 - b);
        const double h = pixelHue(image, x, y);
        ASSERT_GE(h, 0.0) << "body " << b << ": grey pixel at " << x << "," << y;
        // Shading scales the colour (hue kept) and adds a little white highlight (saturation lost,
        // hue kept): the hue must be the body's, within 25°.
        EXPECT_LT(hueDistance(h, hue(own.r, own.g, own.b)), 25.0) << "body " << b << " at " << x << "," << y;
        EXPECT_GT(hueDistance(h, hue(other.r, other.g, other.b)), 60.0) << "body " << b;
    }
    // Every node of the initial state is in the picture (the automatic framing).
    for (const Body& body : scene.bodies)
        for (const glm::dvec3& node : body.positions) {
            const glm::dvec3 p = view.project(node, image.width, image.height);
            EXPECT_TRUE(p.x > 0 && p.x < image.width && p.y > 0 && p.y < image.height && p.z > -1 && p.z < 1);
        }
    // The top corners look at the sky: background.
    const glm::vec3 bg = SceneRenderer::backgroundColour();
    for (int x : {0, image.width - 1}) {
        const auto px = image.pixel(x, 0);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(px[static_cast<std::size_t>(c)], bg[c] * 255.0f, 1.0) << "corner x=" << x;
    }
    // The grid is visible below the bodies: the bottom-centre pixel is floor, neither sky nor body.
    const auto floor = image.pixel(image.width / 2, image.height - 2);
    EXPECT_LT(floor[0], 250);
    EXPECT_NEAR(floor[0], floor[1], 3); // a grey
    EXPECT_NEAR(floor[0], floor[2], 3);
}

TEST(RenderGl, IntersectingFacesAreHighlightedOnlyWhenBodiesIntersect) {
    for (const bool overlap : {false, true}) {
        Engine engine(twoBoxes(overlap ? 0.25 : 0.7, true));
        engine.detectCollisions();
        const auto pairs = engine.readIntersectingPairs();
        SceneRenderer renderer(engine, {160, 120, 4});
        const Image image = renderer.renderFrame(engine);
        if (overlap) {
            ASSERT_FALSE(pairs.empty());
            EXPECT_GT(renderer.highlightedFaces(), 0u);
            EXPECT_GT(highlightPixels(image), 20u);
        } else {
            EXPECT_TRUE(pairs.empty());
            EXPECT_EQ(renderer.highlightedFaces(), 0u);
            EXPECT_EQ(highlightPixels(image), 0u);
        }
    }
}

TEST(RenderGl, ExplicitPairsAreHighlighted) {
    Engine engine(twoBoxes(0.7, false));
    SceneRenderer renderer(engine, {96, 72, 0});
    EXPECT_EQ(highlightPixels(renderer.renderFrame(engine, {})), 0u);
    std::vector<std::array<std::uint32_t, 2>> all;
    for (std::uint32_t f = 0; f + 1 < engine.faceCount(); f += 2) all.push_back({f, f + 1});
    all.push_back({engine.faceCount() + 5, 0}); // out of range: ignored
    const Image image = renderer.renderFrame(engine, all);
    EXPECT_EQ(renderer.highlightedFaces(), engine.faceCount() - engine.faceCount() % 2);
    EXPECT_GT(highlightPixels(image), 200u);
}

TEST(RenderGl, CameraFromTheSceneFile) {
    Scene scene = twoBoxes(0.7, false);
    scene.camera = CameraSettings{{0.0, 1.0, 3.0}, {0.0, 0.2, 0.0}, {0.0, 1.0, 0.0}, 30.0};
    Engine engine(scene);
    SceneRenderer renderer(engine, {120, 90, 0});
    const render::View& view = renderer.view();
    EXPECT_EQ(view.eye, scene.camera->eye);
    EXPECT_EQ(view.fovDeg, 30.0);
    const glm::dvec3 centre = view.project(scene.camera->target, 120, 90);
    EXPECT_NEAR(centre.x, 60.0, 1e-9);
    EXPECT_NEAR(centre.y, 45.0, 1e-9);
    // Straight ahead from x = 0, the left box is left of the centre and the right box right of it.
    const Image image = renderer.renderFrame(engine);
    const double left = view.project(centroid(scene.bodies[0]), 120, 90).x;
    const double right = view.project(centroid(scene.bodies[1]), 120, 90).x;
    EXPECT_LT(left, 60.0);
    EXPECT_GT(right, 60.0);
    const glm::vec3 blue = SceneRenderer::bodyColour(0);
    const glm::dvec3 p = view.project(centroid(scene.bodies[0]), 120, 90);
    EXPECT_LT(hueDistance(pixelHue(image, int(p.x), int(p.y)), hue(blue.r, blue.g, blue.b)), 25.0);

    scene.camera->up = {0.0, 0.0, 0.0};
    Engine bad(scene);
    EXPECT_THROW((void)SceneRenderer(bad, {16, 16, 0}), Error);
}

// Smooth shading (issue 25): on a curved surface (a 1,280-face sphere seen from the side) the
// flat-shaded facets show as steps in brightness between neighbouring pixels; interpolated vertex
// normals make the brightness vary smoothly. Counted inside the sphere's silhouette (pixels whose
// 8 neighbours are all on the sphere): steps of more than 6/255 in luminance between horizontal
// neighbours. Flat shading must show many (facet edges), smooth a fraction of them.
std::size_t brightnessSteps(const Image& image) {
    const auto luminance = [&](int x, int y) {
        const auto p = image.pixel(x, y);
        return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    };
    const auto onSphere = [&](int x, int y) {
        const auto p = image.pixel(x, y);
        return p[2] > p[0] + 40; // the blue body colour, not the white background or grey grid
    };
    std::size_t steps = 0;
    for (int y = 1; y + 1 < image.height; ++y)
        for (int x = 1; x + 1 < image.width; ++x) {
            bool inside = true;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1; ++dx) inside = inside && onSphere(x + dx, y + dy);
            if (inside && std::abs(luminance(x + 1, y) - luminance(x, y)) > 6.0) ++steps;
        }
    return steps;
}

TEST(RenderGl, SmoothShadingHidesTheFacetsOfACurvedSurface) {
    const Scene scene = parseScene(R"({"format_version": 1, "name": "ball", "effects": [],
      "camera": {"eye": [0, 0.4, 1.6], "target": [0, 0.4, 0]},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.3, "subdivisions": 3},
                   "transform": {"translate": [0, 0.4, 0]}, "mass": 1}]})",
                                   ".", "ball");
    Engine engine(scene);
    const std::size_t flat = brightnessSteps(SceneRenderer(engine, {200, 150, 0, false}).renderFrame(engine));
    const std::size_t smooth =
        brightnessSteps(SceneRenderer(engine, {200, 150, 0, true}).renderFrame(engine));
    RecordProperty("flat_steps", static_cast<int>(flat));
    RecordProperty("smooth_steps", static_cast<int>(smooth));
    EXPECT_GT(flat, 50u) << "the facets must show when flat, or the test shows nothing";
    EXPECT_LT(smooth * 4, flat) << "smooth " << smooth << " steps, flat " << flat;
}

// The back side of a face (a cloth's underside) is drawn in a paler colour than its front: the
// same cloth, seen from above, turned with its front up and with its back up (the grid below the
// scene would hide it from underneath); the saturation of its centre pixel.
TEST(RenderGl, TheBackOfAClothIsPaler) {
    const auto saturationAtCentre = [](int rotateXDeg) {
        Scene scene = parseScene(R"({"format_version": 1, "name": "sheet", "effects": [],
          "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]},
                       "transform": {"translate": [0, 0.5, 0], "rotate_deg": [)" +
                                     std::to_string(rotateXDeg) + R"(, 0, 0]}, "mass": 1}]})",
                                 ".", "sheet");
        scene.camera = CameraSettings{{0.0, 2.0, 0.0}, {0.0, 0.5, 0.0}, {0.0, 0.0, 1.0}, 40.0};
        Engine engine(scene);
        const Image image = SceneRenderer(engine, {64, 64, 0}).renderFrame(engine);
        const auto p = image.pixel(32, 32);
        const double mx = std::max({p[0], p[1], p[2]}), mn = std::min({p[0], p[1], p[2]});
        return mx > 0 ? (mx - mn) / mx : 0.0;
    };
    const double a = saturationAtCentre(90), b = saturationAtCentre(-90);
    RecordProperty("saturation_plus_90", std::to_string(a));
    RecordProperty("saturation_minus_90", std::to_string(b));
    // One side is the front (the body colour), the other tinted halfway towards a pale grey.
    EXPECT_LT(std::min(a, b), 0.75 * std::max(a, b)) << "turned +90: " << a << ", -90: " << b;
}

TEST(RenderGl, BadSizesAreErrors) {
    Engine engine(twoBoxes(0.7, false));
    EXPECT_THROW((void)SceneRenderer(engine, {0, 10, 0}), Error);
    EXPECT_THROW((void)SceneRenderer(engine, {10, -1, 0}), Error);
    EXPECT_THROW((void)SceneRenderer(engine, {1 << 20, 10, 0}), Error);
}

TEST(RenderGl, PngRoundTrip) {
    Engine engine(twoBoxes(0.7, false));
    SceneRenderer renderer(engine, {40, 30, 4});
    const Image image = renderer.renderFrame(engine);
    const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "render_roundtrip.png";
    render::writePng(path, image);
    const Loaded back = loadPng(path);
    ASSERT_EQ(back.width, 40);
    ASSERT_EQ(back.height, 30);
    for (std::size_t i = 0; i < 40u * 30u; ++i)
        for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(back.rgb[3 * i + c], image.rgba[4 * i + c]);
    EXPECT_THROW(render::writePng(std::filesystem::path(::testing::TempDir()) / "no/such/dir/x.png", image),
                 Error);
}

TEST(RenderGl, LeavesTheHostsGlStateAsItWas) {
    Engine engine(twoBoxes(0.25, true));
    SceneRenderer renderer(engine, {64, 48, 4});

    // A host's state, deliberately far from the defaults.
    GLuint hostFbo = 0, hostRb = 0, hostVao = 0, hostBuffer = 0, hostTexture = 0;
    glGenRenderbuffers(1, &hostRb);
    glBindRenderbuffer(GL_RENDERBUFFER, hostRb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 8, 8);
    glGenFramebuffers(1, &hostFbo);
    glBindFramebuffer(GL_FRAMEBUFFER, hostFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, hostRb);
    glGenVertexArrays(1, &hostVao);
    glBindVertexArray(hostVao);
    glGenBuffers(1, &hostBuffer);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, hostBuffer);
    GLint align = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    glBufferData(GL_SHADER_STORAGE_BUFFER, 4 * align, nullptr, GL_STATIC_DRAW);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, hostBuffer, align, 2 * align);
    glBindBuffer(GL_ARRAY_BUFFER, hostBuffer);
    glGenTextures(1, &hostTexture);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, hostTexture);
    glActiveTexture(GL_TEXTURE3);
    glViewport(1, 2, 3, 4);
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);

    engine.detectCollisions(); // the engine's own passes may change state too; measure after them
    GLint program = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    GLint ssboGeneric = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &ssboGeneric);
    GLint copyRead = 0, copyWrite = 0;
    glGetIntegerv(GL_COPY_READ_BUFFER_BINDING, &copyRead);
    glGetIntegerv(GL_COPY_WRITE_BUFFER_BINDING, &copyWrite);
    GLint ssbo0 = 0;
    GLint64 start = 0, size = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &ssbo0);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 0, &start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 0, &size);

    const Image image = renderer.renderFrame(engine);
    EXPECT_GT(highlightPixels(image), 0u); // it did draw

    const auto geti = [](GLenum e) {
        GLint v = 0;
        glGetIntegerv(e, &v);
        return v;
    };
    EXPECT_EQ(geti(GL_DRAW_FRAMEBUFFER_BINDING), GLint(hostFbo));
    EXPECT_EQ(geti(GL_READ_FRAMEBUFFER_BINDING), GLint(hostFbo));
    EXPECT_EQ(geti(GL_RENDERBUFFER_BINDING), GLint(hostRb));
    EXPECT_EQ(geti(GL_VERTEX_ARRAY_BINDING), GLint(hostVao));
    EXPECT_EQ(geti(GL_CURRENT_PROGRAM), program);
    EXPECT_EQ(geti(GL_ARRAY_BUFFER_BINDING), GLint(hostBuffer));
    EXPECT_EQ(geti(GL_SHADER_STORAGE_BUFFER_BINDING), ssboGeneric);
    EXPECT_EQ(geti(GL_COPY_READ_BUFFER_BINDING), copyRead);
    EXPECT_EQ(geti(GL_COPY_WRITE_BUFFER_BINDING), copyWrite);
    GLint ssbo0After = 0;
    GLint64 startAfter = 0, sizeAfter = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &ssbo0After);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 0, &startAfter);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 0, &sizeAfter);
    EXPECT_EQ(ssbo0After, ssbo0);
    EXPECT_EQ(startAfter, start);
    EXPECT_EQ(sizeAfter, size);
    EXPECT_EQ(geti(GL_ACTIVE_TEXTURE), GL_TEXTURE3);
    glActiveTexture(GL_TEXTURE0);
    EXPECT_EQ(geti(GL_TEXTURE_BINDING_2D), GLint(hostTexture));
    std::array<GLint, 4> viewport{};
    glGetIntegerv(GL_VIEWPORT, viewport.data());
    EXPECT_EQ(viewport, (std::array<GLint, 4>{1, 2, 3, 4}));
    std::array<GLfloat, 4> clear{};
    glGetFloatv(GL_COLOR_CLEAR_VALUE, clear.data());
    EXPECT_EQ(clear, (std::array<GLfloat, 4>{0.1f, 0.2f, 0.3f, 0.4f}));
    EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_FALSE(glIsEnabled(GL_POLYGON_OFFSET_FILL));
    EXPECT_EQ(geti(GL_DEPTH_FUNC), GL_GREATER);
    GLboolean depthMask = GL_TRUE;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    EXPECT_EQ(depthMask, GL_FALSE);
    std::array<GLboolean, 4> colorMask{};
    glGetBooleanv(GL_COLOR_WRITEMASK, colorMask.data());
    EXPECT_EQ(colorMask, (std::array<GLboolean, 4>{GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE}));
    EXPECT_EQ(geti(GL_PACK_ALIGNMENT), 1);

    // Back to the defaults for the next tests.
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glClearColor(0, 0, 0, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glDeleteTextures(1, &hostTexture);
    glDeleteBuffers(1, &hostBuffer);
    glDeleteVertexArrays(1, &hostVao);
    glDeleteFramebuffers(1, &hostFbo);
    glDeleteRenderbuffers(1, &hostRb);
}

// glcollide view draws through SceneRenderer::draw into the window's framebuffer, with overlays and
// its own view: into a host's framebuffer it draws there (the picture changes with the view) and
// leaves the state the overlays touch (polygon mode, line offset, point size from the shader) as it was.
TEST(RenderGl, DrawsIntoAHostsFramebufferWithOverlaysAndLeavesItsState) {
    Engine engine(twoBoxes(0.25, false));
    SceneRenderer renderer(engine, {1, 1, 0});
    constexpr int kWidth = 64, kHeight = 48;
    GLuint fbo = 0;
    std::array<GLuint, 2> rb{};
    glGenRenderbuffers(2, rb.data());
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kWidth, kHeight);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_POINT); // a host's unusual state
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDisable(GL_POLYGON_OFFSET_LINE);

    render::Overlays overlays;
    overlays.wireframe = true;
    overlays.pinnedNodes = true;
    overlays.segment = {{glm::dvec3(0.0), glm::dvec3(0.3, 0.3, 0.0)}};
    overlays.pairLines = {{glm::vec3(-0.3f, 0.2f, 0.0f), glm::vec3(0.3f, 0.2f, 0.0f)}};
    const auto drawAndRead = [&] {
        // Magenta first: a pixel left magenta was not drawn (draw() clears its whole target).
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        renderer.draw(engine, {}, {fbo, kWidth, kHeight}, overlays);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        const Image image = render::readPixels(kWidth, kHeight);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        return image;
    };
    const Image first = drawAndRead();
    std::size_t magenta = 0, blue = 0, green = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const auto p = first.pixel(x, y);
            magenta += p[0] == 255 && p[1] == 0 && p[2] == 255;
            // The first box's blue (palette 0) lit or in shade has blue above red by about 90 of
            // 255; the grid and the background are neutral grey (r = g = b).
            blue += p[2] > p[0] + 15;
            // The pair lines' green (0, 191, 51), drawn unlit over everything: exact.
            green += p[0] == 0 && p[1] == 191 && p[2] == 51;
        }
    EXPECT_EQ(magenta, 0u);
    EXPECT_GT(blue, 0u);
    EXPECT_GT(green, 0u);
    EXPECT_EQ(glm::vec3(0.0f, 191.0f, 51.0f), glm::round(SceneRenderer::pairLineColour() * 255.0f));

    GLint mode[2] = {};
    glGetIntegerv(GL_POLYGON_MODE, mode);
    EXPECT_EQ(mode[0], GL_POINT);
    EXPECT_TRUE(glIsEnabled(GL_PROGRAM_POINT_SIZE));
    EXPECT_FALSE(glIsEnabled(GL_POLYGON_OFFSET_LINE));
    GLint drawFbo = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo);
    EXPECT_EQ(drawFbo, 0);

    // Another view, another picture.
    const render::View v = renderer.view();
    renderer.setView(render::lookAtView(v.target + 1.5 * (v.eye - v.target), v.target, v.up, v.fovDeg,
                                        v.nearPlane, 2.0 * v.farPlane, double(kWidth) / kHeight));
    EXPECT_NE(drawAndRead().rgba, first.rgba);

    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb.data());
}

} // namespace
} // namespace glcollide
