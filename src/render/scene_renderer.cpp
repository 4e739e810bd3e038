#include "render/scene_renderer.hpp"

#include "gl/debug_output.hpp"
#include "gl/handles.hpp"
#include "render/render_shaders.hpp"
#include "render/saved_gl_state.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

namespace glcollide::render {
namespace {

using gl::GLname;

void deleteVertexArray(GLname name) {
    glDeleteVertexArrays(1, &name);
}
void deleteFramebuffer(GLname name) {
    glDeleteFramebuffers(1, &name);
}
void deleteRenderbuffer(GLname name) {
    glDeleteRenderbuffers(1, &name);
}
void deleteTexture(GLname name) {
    glDeleteTextures(1, &name);
}

using VertexArray = gl::Handle<deleteVertexArray>;
using Framebuffer = gl::Handle<deleteFramebuffer>;
using Renderbuffer = gl::Handle<deleteRenderbuffer>;
using Texture = gl::Handle<deleteTexture>;
using Program = gl::Handle<gl::deleteProgram>;

// The one indexed SSBO binding and texture unit the renderer uses (both restored after drawing).
constexpr GLuint kStyleBinding = 0;           // surface.frag: per-face style
constexpr GLuint kPositionsBinding = 1;       // surface.vert: the engine's positions (smooth shading)
constexpr GLuint kFacesBinding = 2;           // surface.vert: the engine's faces
constexpr GLuint kNodeFaceOffsetsBinding = 3; // surface.vert: node -> face incidence, offsets
constexpr GLuint kNodeFaceListBinding = 4;    // surface.vert: node -> face incidence, faces
static_assert(kNodeFaceListBinding < SavedGlState::kStorageBindings);
constexpr GLuint kShadowUnit = 0;
constexpr int kShadowMapSize = 2048;
constexpr std::uint32_t kHighlightBit = 0x80000000u;

// Tableau 10 without its red, which is the highlight colour; every entry has a clear dominant
// channel or hue, so bodies side by side never look alike.
const std::array<glm::vec3, 10> kPalette = {{
    {0.306f, 0.475f, 0.655f}, // blue
    {0.949f, 0.557f, 0.169f}, // orange
    {0.349f, 0.631f, 0.310f}, // green
    {0.690f, 0.478f, 0.631f}, // purple
    {0.463f, 0.718f, 0.698f}, // teal
    {0.929f, 0.788f, 0.282f}, // yellow
    {0.612f, 0.459f, 0.373f}, // brown
    {1.000f, 0.616f, 0.655f}, // pink
    {0.729f, 0.690f, 0.675f}, // grey
    {0.200f, 0.300f, 0.500f}, // navy
}};
const glm::vec3 kHighlight{0.890f, 0.102f, 0.110f};
const glm::vec3 kBackground{1.0f, 1.0f, 1.0f};
const glm::vec3 kBackTint{0.95f, 0.92f, 0.80f}; // a pale warm grey: the back side of a face, halfway
const glm::vec3 kPairLine{0.0f, 0.75f, 0.2f};   // green: no body's colour and not the highlight red
const glm::vec3 kContactLine{0.0f, 0.8f, 0.9f}; // cyan: neither a body's colour, the pairs' nor the pull's
const glm::vec3 kBoxLine{0.5f, 0.2f, 0.8f};     // violet: the broad phase's boxes, behind the rest

struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
    void add(const glm::dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    [[nodiscard]] bool empty() const { return !(lo.x <= hi.x); }
    [[nodiscard]] glm::dvec3 centre() const { return 0.5 * (lo + hi); }
    /// Half the diagonal, at least 1 mm (a single node still gets a view).
    [[nodiscard]] double radius() const { return std::max(0.5 * glm::length(hi - lo), 1e-3); }
};

Box nodeBox(const Scene& scene) {
    Box box;
    for (const Body& b : scene.bodies)
        for (const glm::dvec3& p : b.positions) box.add(p);
    if (box.empty()) box.add(glm::dvec3(0.0));
    return box;
}

/// The nodes' box, reaching down (or up) to the ground plane when the ground effect is on.
Box framedBox(const Scene& scene) {
    Box box = nodeBox(scene);
    if (scene.effects.has(Effect::Ground)) {
        box.lo.y = std::min(box.lo.y, scene.ground.height);
        box.hi.y = std::max(box.hi.y, scene.ground.height);
    }
    return box;
}

/// The smallest of 1, 2, 5 times a power of ten that is >= x (> 0).
double niceStep(double x) {
    const double decade = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * decade >= x * (1.0 - 1e-9)) return m * decade;
    return 10.0 * decade;
}

void finishView(View& v, const Scene& scene, double aspect) {
    const glm::dvec3 forward = v.target - v.eye;
    if (!(glm::length(forward) > 0.0)) throw Error(scene.name + ": camera eye and target coincide");
    if (!(glm::length(v.up) > 0.0) ||
        glm::length(glm::cross(glm::normalize(forward), glm::normalize(v.up))) < 1e-6)
        throw Error(scene.name + ": camera up is zero or parallel to the view direction");
    if (!(v.fovDeg > 0.0 && v.fovDeg < 180.0))
        throw Error(scene.name + ": camera fov_deg must be in (0, 180)");
    // Depth range: everything within the framed box and the grid square, seen from the eye.
    const Box box = framedBox(scene);
    const Grid grid = sceneGrid(scene);
    v.farPlane = glm::length(v.eye - box.centre()) + box.radius() + 1.5 * grid.halfSize;
    v.nearPlane = v.farPlane / 1000.0;
    v = lookAtView(v.eye, v.target, v.up, v.fovDeg, v.nearPlane, v.farPlane, aspect);
}

std::string infoLog(GLuint object, bool isProgram) {
    GLint length = 0;
    if (isProgram)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    if (isProgram)
        glGetProgramInfoLog(object, length, nullptr, log.data());
    else
        glGetShaderInfoLog(object, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

Program buildProgram(const char* vertexFile, const char* fragmentFile) {
    Program program(glCreateProgram());
    std::array<GLuint, 2> shaders{};
    const std::array<std::pair<GLenum, const char*>, 2> stages = {
        {{GL_VERTEX_SHADER, vertexFile}, {GL_FRAGMENT_SHADER, fragmentFile}}};
    for (std::size_t i = 0; i < stages.size(); ++i) {
        const char* source = embeddedShaderSource(stages[i].second);
        if (source == nullptr)
            throw Error(std::string("no embedded shader shaders/render/") + stages[i].second);
        const GLuint shader = glCreateShader(stages[i].first);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE) {
            const std::string log = infoLog(shader, false);
            glDeleteShader(shader);
            for (std::size_t k = 0; k < i; ++k) glDeleteShader(shaders[k]);
            throw Error(std::string("shaders/render/") + stages[i].second + ": compile error:\n" + log);
        }
        shaders[i] = shader;
        glAttachShader(program.name(), shader);
    }
    glLinkProgram(program.name());
    for (GLuint s : shaders) {
        glDetachShader(program.name(), s);
        glDeleteShader(s);
    }
    GLint ok = GL_FALSE;
    glGetProgramiv(program.name(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE)
        throw Error(std::string("shaders/render/") + vertexFile + " + " + fragmentFile + ": link error:\n" +
                    infoLog(program.name(), true));
    gl::labelObject(GL_PROGRAM, program.name(), std::string("glcollide/render/") + fragmentFile);
    return program;
}

GLint location(const Program& p, const char* name) {
    return glGetUniformLocation(p.name(), name);
}

void setMat4(const Program& p, const char* name, const glm::dmat4& m) {
    const glm::mat4 f(m);
    glProgramUniformMatrix4fv(p.name(), location(p, name), 1, GL_FALSE, glm::value_ptr(f));
}
void setVec3(const Program& p, const char* name, const glm::dvec3& v) {
    glProgramUniform3f(p.name(), location(p, name), static_cast<float>(v.x), static_cast<float>(v.y),
                       static_cast<float>(v.z));
}
void setFloat(const Program& p, const char* name, double v) {
    glProgramUniform1f(p.name(), location(p, name), static_cast<float>(v));
}

Renderbuffer makeRenderbuffer(GLenum format, int samples, int width, int height) {
    GLuint name = 0;
    glGenRenderbuffers(1, &name);
    Renderbuffer rb(name);
    glBindRenderbuffer(GL_RENDERBUFFER, name);
    if (samples > 0)
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
    else
        glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    return rb;
}

Framebuffer makeFramebuffer(const char* label) {
    GLuint name = 0;
    glGenFramebuffers(1, &name);
    glBindFramebuffer(GL_FRAMEBUFFER, name);
    gl::labelObject(GL_FRAMEBUFFER, name, std::string("glcollide/render/") + label);
    return Framebuffer(name);
}

void checkComplete(const char* what) {
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("render: the ") + what + " framebuffer is incomplete (status 0x" + [&] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%04X", status);
            return std::string(buf);
        }() + ")");
}

} // namespace

Image readPixels(int width, int height) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    Image image;
    image.width = width;
    image.height = height;
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    std::vector<std::uint8_t> bottomUp(row * static_cast<std::size_t>(image.height));
    glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    image.rgba.resize(bottomUp.size());
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y)
        std::copy_n(bottomUp.data() + (static_cast<std::size_t>(image.height) - 1 - y) * row, row,
                    image.rgba.data() + y * row);
    return image;
}

std::array<std::uint8_t, 4> Image::pixel(int x, int y) const {
    const std::size_t i =
        (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

glm::dvec3 View::project(const glm::dvec3& world, int width, int height) const {
    const glm::dvec4 clip = viewProjection() * glm::dvec4(world, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return {(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height, ndc.z};
}

bool View::inFront(const glm::dvec3& world) const {
    return (viewProjection() * glm::dvec4(world, 1.0)).w > 0.0;
}

View lookAtView(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double fovDeg,
                double nearPlane, double farPlane, double aspect) {
    View v;
    v.eye = eye;
    v.target = target;
    v.up = up;
    v.fovDeg = fovDeg;
    v.nearPlane = nearPlane;
    v.farPlane = farPlane;
    v.viewMatrix = glm::lookAt(eye, target, up);
    v.projection = glm::perspective(glm::radians(fovDeg), aspect, nearPlane, farPlane);
    return v;
}

Grid sceneGrid(const Scene& scene) {
    const Box nodes = nodeBox(scene);
    const Box framed = framedBox(scene);
    Grid g;
    const double y =
        scene.effects.has(Effect::Ground) ? scene.ground.height : nodes.lo.y - 0.02 * nodes.radius();
    g.centre = {framed.centre().x, y, framed.centre().z};
    g.halfSize = 3.0 * framed.radius();
    g.spacing = niceStep(g.halfSize / 20.0);
    return g;
}

View sceneView(const Scene& scene, double aspect) {
    View v;
    if (scene.camera) {
        v.eye = scene.camera->eye;
        v.target = scene.camera->target;
        v.up = scene.camera->up;
        v.fovDeg = scene.camera->fovDeg;
        finishView(v, scene, aspect);
        return v;
    }
    const Box box = framedBox(scene);
    const double azimuth = glm::radians(35.0), elevation = glm::radians(25.0);
    const glm::dvec3 toEye{std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                           std::cos(azimuth) * std::cos(elevation)};
    v.fovDeg = 40.0;
    v.target = box.centre();
    v.up = {0.0, 1.0, 0.0};
    const glm::dvec3 right = glm::normalize(glm::cross(-toEye, v.up));
    const glm::dvec3 up = glm::cross(right, -toEye);
    // 8 % margin on every side.
    const double tanY = std::tan(glm::radians(v.fovDeg) / 2.0) * 0.92;
    const double tanX = tanY * aspect;
    double distance = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p{(corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                           (corner & 4) ? box.hi.z : box.lo.z};
        const glm::dvec3 q = p - v.target;
        const double z = glm::dot(q, toEye); // towards the eye
        distance = std::max(
            {distance, z + std::abs(glm::dot(q, right)) / tanX, z + std::abs(glm::dot(q, up)) / tanY});
    }
    distance = std::max(distance, 1e-3);
    v.eye = v.target + toEye * distance;
    finishView(v, scene, aspect);
    return v;
}

struct SceneRenderer::Impl {
    RenderOptions options;
    int samples = 0;
    View view;
    Grid grid;
    std::uint32_t nodeCount = 0;
    std::uint32_t faceCount = 0;
    std::vector<std::uint32_t> faceObject;
    std::vector<std::uint32_t> faceStyle;
    std::size_t highlighted = 0;

    glm::dvec3 sceneCentre{0.0}; ///< the framed box's centre: the shadow map looks at it

    Program surface, depth, gridProgram, overlay;
    VertexArray meshArray, emptyArray, lineArray;
    GLuint lineBuffer = 0; ///< Overlays::pairLines, re-specified per frame (deleted with the renderer)
    ~Impl() {
        if (lineBuffer != 0) glDeleteBuffers(1, &lineBuffer);
    }
    gl::Buffer styleBuffer;
    gl::Buffer nodeFaceOffsets, nodeFaceList; ///< smooth shading: each node's faces (surface.vert)
    Renderbuffer colour, depthBuffer, resolvedColour;
    Framebuffer target, resolve, shadowTarget;
    Texture shadowMap;
    glm::dmat4 lightViewProjection{1.0};

    void applyView();
    void drawInto(const Engine& engine, std::span<const std::array<std::uint32_t, 2>> highlightedPairs,
                  const DrawTarget& into, const Overlays& overlays);
};

SceneRenderer::SceneRenderer(const Engine& engine, const RenderOptions& options)
    : m_impl(std::make_unique<Impl>()) {
    Impl& m = *m_impl;
    m.options = options;
    GLint maxSize = 0, maxSamples = 0;
    std::array<GLint, 2> maxViewport{};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport.data());
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    const int limit = std::min({maxSize, maxViewport[0], maxViewport[1]});
    if (options.width < 1 || options.height < 1 || options.width > limit || options.height > limit)
        throw Error("render size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                    " is outside 1 ... " + std::to_string(limit) + " pixels per side on this device");
    m.samples = std::min(options.samples, static_cast<int>(maxSamples));
    if (m.samples <= 1) m.samples = 0;

    const Scene& scene = engine.scene();
    m.view = sceneView(scene, static_cast<double>(options.width) / options.height);
    m.grid = sceneGrid(scene);
    m.nodeCount = engine.nodeCount();
    m.faceCount = engine.faceCount();
    const std::vector<std::uint32_t> firstFaces = engine.bodyFirstFaces();
    m.faceObject.assign(m.faceCount, 0);
    for (std::size_t b = 0; b < firstFaces.size(); ++b) {
        const std::uint32_t end = b + 1 < firstFaces.size() ? firstFaces[b + 1] : m.faceCount;
        for (std::uint32_t f = firstFaces[b]; f < end && f < m.faceCount; ++f)
            m.faceObject[f] = static_cast<std::uint32_t>(b) & ~kHighlightBit;
    }
    m.faceStyle = m.faceObject;

    const SavedGlState saved(kShadowUnit);
    gl::DebugGroup group("glcollide::render::SceneRenderer");
    m.surface = buildProgram("surface.vert", "surface.frag");
    m.depth = buildProgram("surface.vert", "depth.frag");
    m.gridProgram = buildProgram("grid.vert", "grid.frag");
    m.overlay = buildProgram("overlay.vert", "overlay.frag");
    m.styleBuffer =
        gl::Buffer("render/faceStyle", m.faceStyle.size() * sizeof(std::uint32_t), m.faceStyle.data());
    // Each node's faces in global face order (CSR), for surface.vert's vertex normals: the
    // engine's face buffer holds the bodies' faces in body order, node indices global.
    {
        std::vector<std::uint32_t> faceNodes;
        const std::vector<std::uint32_t> firstNodes = engine.bodyFirstNodes();
        for (std::size_t b = 0; b < scene.bodies.size(); ++b)
            for (const auto& f : scene.bodies[b].faces)
                for (int k = 0; k < 3; ++k) faceNodes.push_back(firstNodes[b] + f[k]);
        std::vector<std::uint32_t> offsets(std::size_t{m.nodeCount} + 1, 0u), list(faceNodes.size());
        for (std::uint32_t n : faceNodes) ++offsets[n + 1];
        for (std::size_t i = 0; i < m.nodeCount; ++i) offsets[i + 1] += offsets[i];
        std::vector<std::uint32_t> next(offsets.begin(), offsets.end() - 1);
        for (std::size_t c = 0; c < faceNodes.size(); ++c)
            list[next[faceNodes[c]]++] = static_cast<std::uint32_t>(c / 3);
        if (list.empty()) list.push_back(0u); // GL rejects zero-size storage
        m.nodeFaceOffsets = gl::makeBuffer("render/nodeFaceOffsets", offsets);
        m.nodeFaceList = gl::makeBuffer("render/nodeFaceList", list);
    }

    GLuint vao = 0;
    glGenVertexArrays(1, &vao);
    m.meshArray = VertexArray(vao);
    glBindVertexArray(vao);
    gl::labelObject(GL_VERTEX_ARRAY, vao, "glcollide/render/mesh");
    // The engine's position buffer, bound per frame: attribute 0 = vec4 (xyz, inverse mass).
    glEnableVertexAttribArray(0);
    glVertexAttribFormat(0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribBinding(0, 0);
    glGenVertexArrays(1, &vao);
    m.emptyArray = VertexArray(vao);

    m.colour = makeRenderbuffer(GL_RGBA8, m.samples, options.width, options.height);
    m.depthBuffer = makeRenderbuffer(GL_DEPTH_COMPONENT24, m.samples, options.width, options.height);
    m.target = makeFramebuffer("target");
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.colour.name());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depthBuffer.name());
    checkComplete("colour");
    if (m.samples > 0) {
        m.resolvedColour = makeRenderbuffer(GL_RGBA8, 0, options.width, options.height);
        m.resolve = makeFramebuffer("resolve");
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  m.resolvedColour.name());
        checkComplete("resolve");
    }

    GLuint tex = 0;
    glGenTextures(1, &tex);
    m.shadowMap = Texture(tex);
    glActiveTexture(GL_TEXTURE0 + kShadowUnit);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl::labelObject(GL_TEXTURE, tex, "glcollide/render/shadowMap");
    m.shadowTarget = makeFramebuffer("shadow");
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, tex, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    checkComplete("shadow");

    m.sceneCentre = framedBox(scene).centre();
    std::array<float, 3 * kPalette.size()> palette{};
    for (std::size_t i = 0; i < kPalette.size(); ++i)
        for (int c = 0; c < 3; ++c) palette[3 * i + static_cast<std::size_t>(c)] = kPalette[i][c];
    glProgramUniform3fv(m.surface.name(), location(m.surface, "u_palette[0]"),
                        static_cast<GLsizei>(kPalette.size()), palette.data());
    setVec3(m.surface, "u_highlight", glm::dvec3(kHighlight));
    setVec3(m.surface, "u_backTint", glm::dvec3(kBackTint));
    glProgramUniform1ui(m.depth.name(), location(m.depth, "u_smooth"), 0u);
    glProgramUniform1i(m.surface.name(), location(m.surface, "u_shadowMap"), static_cast<GLint>(kShadowUnit));
    setVec3(m.gridProgram, "u_centre", m.grid.centre);
    setFloat(m.gridProgram, "u_halfSize", m.grid.halfSize);
    setFloat(m.gridProgram, "u_spacing", m.grid.spacing);
    setVec3(m.gridProgram, "u_background", glm::dvec3(kBackground));
    glProgramUniform1i(m.gridProgram.name(), location(m.gridProgram, "u_shadowMap"),
                       static_cast<GLint>(kShadowUnit));
    m.applyView();
}

/// The uniforms that follow the view: the camera's matrix and eye, and the lights, which are fixed
/// relative to the camera so every view is lit alike (with them the shadow map's direction).
void SceneRenderer::Impl::applyView() {
    glProgramUniform1ui(surface.name(), location(surface, "u_smooth"), options.smooth ? 1u : 0u);
    // The key light from above,
    // left and in front (it casts the shadows on the grid), a weak fill from the right.
    const glm::dvec3 toEye = glm::normalize(view.eye - view.target);
    const glm::dvec3 worldUp{0.0, 1.0, 0.0};
    glm::dvec3 right = glm::cross(-toEye, worldUp);
    right = glm::length(right) > 1e-6 ? glm::normalize(right) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 keyDir = glm::normalize(-0.45 * right + 1.1 * worldUp + 0.45 * toEye);
    const glm::dvec3 fillDir = glm::normalize(0.7 * right + 0.2 * worldUp + 0.7 * toEye);
    // The shadow map covers the grid's square seen along the key light.
    const double reach = grid.halfSize * 1.2;
    const glm::dvec3 centre = sceneCentre;
    const glm::dvec3 lightUp = std::abs(keyDir.y) > 0.99 ? glm::dvec3(0.0, 0.0, 1.0) : worldUp;
    lightViewProjection = glm::ortho(-reach, reach, -reach, reach, 0.0, 4.0 * reach) *
                          glm::lookAt(centre + keyDir * (2.0 * reach), centre, lightUp);
    const glm::dmat4 bias =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0.5)) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
    const glm::dmat4 shadowMatrix = bias * lightViewProjection;
    const double texel = 1.0 / kShadowMapSize;

    setVec3(surface, "u_eye", view.eye);
    setVec3(surface, "u_keyDir", keyDir);
    setVec3(surface, "u_fillDir", fillDir);
    setMat4(surface, "u_viewProjection", view.viewProjection());
    setMat4(surface, "u_shadowMatrix", shadowMatrix);
    setFloat(surface, "u_shadowTexel", texel);
    setFloat(surface, "u_normalOffset", 2.0 * reach * texel * 1.5);
    setMat4(depth, "u_viewProjection", lightViewProjection);
    setMat4(gridProgram, "u_viewProjection", view.viewProjection());
    setMat4(gridProgram, "u_shadowMatrix", shadowMatrix);
    setFloat(gridProgram, "u_shadowTexel", texel);
}

SceneRenderer::~SceneRenderer() = default;
SceneRenderer::SceneRenderer(SceneRenderer&&) noexcept = default;
SceneRenderer& SceneRenderer::operator=(SceneRenderer&&) noexcept = default;

Image SceneRenderer::renderFrame(const Engine& engine) {
    std::vector<std::array<std::uint32_t, 2>> pairs;
    {
        // The readback is the engine's work, but on the renderer's behalf: leave no trace of it.
        const SavedGlState saved(kShadowUnit);
        pairs = engine.readIntersectingPairs();
    }
    return renderFrame(engine, pairs);
}

Image SceneRenderer::renderFrame(const Engine& engine,
                                 std::span<const std::array<std::uint32_t, 2>> highlightedPairs) {
    Impl& m = *m_impl;
    const SavedGlState saved(kShadowUnit);
    gl::DebugGroup group("glcollide::render::SceneRenderer::renderFrame");
    m.drawInto(engine, highlightedPairs, {m.target.name(), m.options.width, m.options.height}, {});

    GLuint readFrom = m.target.name();
    if (m.samples > 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, m.target.name());
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve.name());
        glBlitFramebuffer(0, 0, m.options.width, m.options.height, 0, 0, m.options.width, m.options.height,
                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
        readFrom = m.resolve.name();
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, readFrom);
    return readPixels(m.options.width, m.options.height);
}

void SceneRenderer::draw(const Engine& engine, std::span<const std::array<std::uint32_t, 2>> highlightedPairs,
                         const DrawTarget& target, const Overlays& overlays) {
    if (target.width < 1 || target.height < 1) return; // a minimised window: nothing to draw
    const SavedGlState saved(kShadowUnit);
    gl::DebugGroup group("glcollide::render::SceneRenderer::draw");
    m_impl->drawInto(engine, highlightedPairs, target, overlays);
}

void SceneRenderer::setView(const View& view) {
    m_impl->view = view;
    m_impl->applyView();
}

void SceneRenderer::setSmooth(bool smooth) {
    m_impl->options.smooth = smooth;
    glProgramUniform1ui(m_impl->surface.name(), location(m_impl->surface, "u_smooth"), smooth ? 1u : 0u);
}

/// Draws into `target` with the state already saved by the caller (renderFrame, draw).
void SceneRenderer::Impl::drawInto(const Engine& engine,
                                   std::span<const std::array<std::uint32_t, 2>> highlightedPairs,
                                   const DrawTarget& into, const Overlays& overlays) {
    if (engine.nodeCount() != nodeCount || engine.faceCount() != faceCount)
        throw Error("SceneRenderer: not the engine the renderer was made for");
    faceStyle = faceObject;
    for (const auto& pair : highlightedPairs)
        for (std::uint32_t f : pair)
            if (f < faceCount) faceStyle[f] |= kHighlightBit;
    highlighted = static_cast<std::size_t>(std::count_if(
        faceStyle.begin(), faceStyle.end(), [](std::uint32_t s) { return (s & kHighlightBit) != 0; }));

    styleBuffer.upload(0, faceStyle.size() * sizeof(std::uint32_t), faceStyle.data());
    // step() already issues this barrier; a caller who changed positions otherwise may not have.
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT);

    for (GLenum cap : {GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_RASTERIZER_DISCARD,
                       GL_SAMPLE_ALPHA_TO_COVERAGE, GL_PRIMITIVE_RESTART, GL_FRAMEBUFFER_SRGB, GL_DEPTH_CLAMP,
                       GL_DITHER, GL_PROGRAM_POINT_SIZE})
        glDisable(cap);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glClearDepth(1.0);

    glBindVertexArray(meshArray.name());
    glBindVertexBuffer(0, engine.positionBuffer(), 0, 16);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, engine.faceIndexBuffer());
    const auto indexCount = static_cast<GLsizei>(3 * faceCount);
    // Smooth shading reads the same two buffers as storage, and the node -> face incidence.
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionsBinding, engine.positionBuffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFacesBinding, engine.faceIndexBuffer());
    nodeFaceOffsets.bindStorage(kNodeFaceOffsetsBinding);
    nodeFaceList.bindStorage(kNodeFaceListBinding);

    // Shadow map: depth seen from the key light, pushed back a little against self-shadowing.
    glBindFramebuffer(GL_FRAMEBUFFER, shadowTarget.name());
    glViewport(0, 0, kShadowMapSize, kShadowMapSize);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 4.0f);
    glUseProgram(depth.name());
    if (indexCount > 0) glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    glDisable(GL_POLYGON_OFFSET_FILL);

    glBindFramebuffer(GL_FRAMEBUFFER, into.framebuffer);
    glViewport(0, 0, into.width, into.height);
    if (samples > 0 || into.framebuffer == 0) glEnable(GL_MULTISAMPLE); // a window's own samples count too
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0 + kShadowUnit);
    glBindTexture(GL_TEXTURE_2D, shadowMap.name());
    glBindSampler(kShadowUnit, 0);
    styleBuffer.bindStorage(kStyleBinding);
    glUseProgram(surface.name());
    glFrontFace(GL_CCW); // faces wind counter-clockwise seen from outside: the front
    if (indexCount > 0) glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);

    // The grid after the surfaces: hidden where they are in front, and pushed back so faces
    // lying on the ground win.
    glBindVertexArray(emptyArray.name());
    glUseProgram(gridProgram.name());
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 2.0f);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindVertexArray(meshArray.name());

    // Overlays over the surfaces, in one colour each: the wireframe's lines are pulled towards the
    // eye by a polygon offset and pass LEQUAL, so their own faces do not bury them.
    const glm::dmat4 viewProjection = view.viewProjection();
    setMat4(overlay, "u_viewProjection", viewProjection);
    glUseProgram(overlay.name());
    if (overlays.wireframe && indexCount > 0) {
        glProgramUniform1ui(overlay.name(), location(overlay, "u_mode"), 0u);
        // Mid grey: seen on a dark face in shade and on a pale back side alike.
        setVec3(overlay, "u_colour", glm::dvec3(0.42));
        glDepthFunc(GL_LEQUAL);
        glEnable(GL_POLYGON_OFFSET_LINE);
        glPolygonOffset(-1.0f, -1.0f);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDisable(GL_POLYGON_OFFSET_LINE);
        glDepthFunc(GL_LESS);
    }
    glEnable(GL_PROGRAM_POINT_SIZE);
    if (overlays.pinnedNodes && nodeCount > 0) {
        glProgramUniform1ui(overlay.name(), location(overlay, "u_mode"), 1u);
        setVec3(overlay, "u_colour", glm::dvec3(0.05, 0.05, 0.05));
        setFloat(overlay, "u_pointSize", 7.0);
        glDisable(GL_DEPTH_TEST); // a pin stays visible behind its cloth
        glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(nodeCount));
        glEnable(GL_DEPTH_TEST);
    }
    // Line sets, each in one colour, through the same stream buffer (re-specified per set).
    const auto drawLines = [&](const std::vector<std::array<glm::vec3, 2>>& lines, glm::vec3 lineColour) {
        if (lines.empty()) return;
        if (lineBuffer == 0) {
            glGenBuffers(1, &lineBuffer);
            GLuint vao = 0;
            glGenVertexArrays(1, &vao);
            lineArray = VertexArray(vao);
            glBindVertexArray(vao);
            glBindBuffer(GL_ARRAY_BUFFER, lineBuffer);
            gl::labelObject(GL_BUFFER, lineBuffer, "glcollide/render/pairLines");
            glEnableVertexAttribArray(0);
            glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr); // w defaults to 1
        }
        glBindVertexArray(lineArray.name());
        glBindBuffer(GL_ARRAY_BUFFER, lineBuffer);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(lines[0])), lines.data(),
                     GL_STREAM_DRAW);
        glProgramUniform1ui(overlay.name(), location(overlay, "u_mode"), 0u);
        setVec3(overlay, "u_colour", glm::dvec3(lineColour));
        glDisable(GL_DEPTH_TEST); // pairs between touching faces lie inside or behind the surfaces
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(2 * lines.size()));
        glEnable(GL_DEPTH_TEST);
        glBindVertexArray(meshArray.name());
    };
    drawLines(overlays.boxLines, kBoxLine);
    drawLines(overlays.pairLines, kPairLine);
    drawLines(overlays.contactLines, kContactLine);
    if (overlays.segment) {
        glBindVertexArray(emptyArray.name());
        glProgramUniform1ui(overlay.name(), location(overlay, "u_mode"), 2u);
        setVec3(overlay, "u_a", (*overlays.segment)[0]);
        setVec3(overlay, "u_b", (*overlays.segment)[1]);
        setVec3(overlay, "u_colour", glm::dvec3(0.85, 0.1, 0.6));
        setFloat(overlay, "u_pointSize", 9.0);
        glDisable(GL_DEPTH_TEST); // the pull's spring is always seen
        glDrawArrays(GL_LINES, 0, 2);
        glDrawArrays(GL_POINTS, 0, 2);
        glEnable(GL_DEPTH_TEST);
    }
}

const View& SceneRenderer::view() const {
    return m_impl->view;
}
const Grid& SceneRenderer::grid() const {
    return m_impl->grid;
}
int SceneRenderer::width() const {
    return m_impl->options.width;
}
int SceneRenderer::height() const {
    return m_impl->options.height;
}
int SceneRenderer::samples() const {
    return m_impl->samples;
}
std::size_t SceneRenderer::highlightedFaces() const {
    return m_impl->highlighted;
}

glm::vec3 SceneRenderer::bodyColour(std::size_t index) {
    return kPalette[index % kPalette.size()];
}
glm::vec3 SceneRenderer::highlightColour() {
    return kHighlight;
}
glm::vec3 SceneRenderer::backTint() {
    return kBackTint;
}

glm::vec3 SceneRenderer::pairLineColour() {
    return kPairLine;
}
glm::vec3 SceneRenderer::contactLineColour() {
    return kContactLine;
}
glm::vec3 SceneRenderer::boxLineColour() {
    return kBoxLine;
}

glm::vec3 SceneRenderer::backgroundColour() {
    return kBackground;
}

} // namespace glcollide::render
