// glcollide embedded in a host renderer.
//
// The host owns everything graphical: it makes its own OpenGL 4.3 context with plain EGL, its own
// shader, vertex array and framebuffer. glcollide::Engine simulates on that context and the host
// draws the engine's GPU buffers directly: positions as the vertex buffer, faces as the index
// buffer. Nothing is copied to the CPU to draw.
//
//   glcollide_embed [OUTPUT_DIR] [FRAMES]
//
// writes OUTPUT_DIR/frame_NNN.ppm (default: the current directory, 48 frames, an image every 16).

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

// libepoxy loads both APIs here; its <epoxy/egl.h> is the plain EGL API (with <EGL/egl.h> it
// would clash). Any GL loader works (glad, GLEW, epoxy): glcollide passes GL names as integers.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

// ---- 1. The host's own context: raw EGL, no window ---------------------------------------------

struct HostContext {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

EGLDisplay openDisplay() {
    // Client extensions (EGL_EXT_platform_base, EGL_EXT_device_enumeration), looked up by name.
    const auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    const auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (getPlatformDisplay == nullptr) return EGL_NO_DISPLAY;
    // Mesa: the surfaceless platform (a GPU's driver, or llvmpipe on the CPU).
    EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
    // NVIDIA: the EGL device platform, first device.
    EGLDeviceEXT device = nullptr;
    EGLint count = 0;
    if (queryDevices != nullptr && queryDevices(1, &device, &count) && count > 0) {
        display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
        if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
    }
    return EGL_NO_DISPLAY;
}

bool createContext(HostContext& host) {
    host.display = openDisplay();
    if (host.display == EGL_NO_DISPLAY || !eglBindAPI(EGL_OPENGL_API)) return false;
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(host.display, configAttribs, &config, 1, &configs) || configs < 1) return false;
    // glcollide needs desktop GL 4.3 core (compute shaders).
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    host.context = eglCreateContext(host.display, config, EGL_NO_CONTEXT, contextAttribs);
    if (host.context == EGL_NO_CONTEXT) return false;
    // No surface (EGL_KHR_surfaceless_context): we render into our own framebuffer object.
    return eglMakeCurrent(host.display, EGL_NO_SURFACE, EGL_NO_SURFACE, host.context) == EGL_TRUE;
}

void destroyContext(HostContext& host) {
    if (host.display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(host.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (host.context != EGL_NO_CONTEXT) eglDestroyContext(host.display, host.context);
    eglTerminate(host.display); // we are the application: terminating the display is ours to do
}

// ---- 2. The host's renderer ---------------------------------------------------------------------

// The vertex attribute is the engine's position buffer as it is: vec4 per node, stride 16,
// xyz in metres (w is the node's inverse mass, unused here).
const char* kVertexShader = R"(#version 430 core
layout(location = 0) in vec4 a_node;
uniform mat4 u_viewProjection;
out vec3 v_world;
void main() {
    v_world = a_node.xyz;
    gl_Position = u_viewProjection * vec4(a_node.xyz, 1.0);
})";

// Flat shading from screen-space derivatives (the engine stores no normals); faces from
// u_firstClothFace on belong to the cloth.
const char* kFragmentShader = R"(#version 430 core
in vec3 v_world;
uniform uint u_firstClothFace;
out vec4 o_color;
void main() {
    vec3 n = normalize(cross(dFdx(v_world), dFdy(v_world)));
    float light = 0.25 + 0.75 * abs(dot(n, normalize(vec3(0.4, 1.0, 0.6))));
    vec3 base = uint(gl_PrimitiveID) >= u_firstClothFace ? vec3(0.95, 0.5, 0.2) : vec3(0.3, 0.55, 0.9);
    o_color = vec4(base * light, 1.0);
})";

constexpr int kWidth = 640, kHeight = 480;
constexpr unsigned char kBackground[3] = {20, 24, 32}; // the smoke test counts pixels of another colour

GLuint compile(GLenum stage, const char* source) {
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        std::fprintf(stderr, "shader: %s\n", log);
    }
    return shader;
}

GLuint linkProgram() {
    const GLuint program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader),
                 fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    return program;
}

// Reads the framebuffer back and writes a binary PPM (rows top to bottom); returns the number of
// pixels that are not the background.
long writePpm(const std::filesystem::path& path) {
    std::vector<unsigned char> rgb(std::size_t{kWidth} * kHeight * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << kWidth << " " << kHeight << "\n255\n";
    long lit = 0;
    for (int y = kHeight - 1; y >= 0; --y) {
        const char* row = reinterpret_cast<const char*>(rgb.data()) + std::size_t(y) * kWidth * 3;
        out.write(row, kWidth * 3);
        for (int x = 0; x < kWidth; ++x)
            if (static_cast<unsigned char>(row[3 * x]) != kBackground[0] ||
                static_cast<unsigned char>(row[3 * x + 1]) != kBackground[1] ||
                static_cast<unsigned char>(row[3 * x + 2]) != kBackground[2])
                ++lit;
    }
    return lit;
}

// A cloth dropped onto a ball that is pinned in place. Implicit Euler at one substep per frame:
// the default contact response (intersection_free) keeps the cloth on the ball at that step.
const char* kScene = R"({
  "format_version": 1, "name": "cloth on a ball",
  "effects": ["gravity", "springs", "damping", "collisions"],
  "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
  "damping": 0.2,
  "collision": {"thickness": 0.02, "stiffness": 1000},
  "objects": [
    {"name": "ball", "generator": {"type": "sphere", "radius": 0.35, "subdivisions": 2}, "mass": 1.0,
     "springs": {"stiffness": 100}, "pinned": {"inside": {"min": [-1, -1, -1], "max": [1, 1, 1]}}},
    {"name": "cloth", "generator": {"type": "cloth", "size": [1.2, 1.2], "resolution": [20, 20]},
     "transform": {"translate": [0, 0.5, 0], "rotate_deg": [90, 0, 0]}, "mass": 0.3,
     "springs": {"stiffness": 200, "damping": 0.002, "shear_stiffness": 80, "bend_stiffness": 2}}]})";

int run(const std::filesystem::path& outputDir, int frames) {
    // ---- 3. The engine, on the host's current context ----
    glcollide::EngineOptions options;
    options.gpuTiming = false; // no per-pass timestamps: step() does not wait for the GPU to time them
    // Opt-in: the engine chains its callback to whatever callback the host had (none here) and
    // restores it when it is destroyed. Without this option it never touches the callback.
    int glErrors = 0;
    options.debugCallback = [&](const glcollide::GlDebugMessage& m) {
        if (m.type != GL_DEBUG_TYPE_ERROR) return;
        ++glErrors;
        std::fprintf(stderr, "GL error: %.*s\n", static_cast<int>(m.text.size()), m.text.data());
    };
    glcollide::Engine engine(glcollide::parseScene(kScene, ".", "embedded scene"), options);
    std::printf("%s: %u nodes, %u faces, %d substeps per frame, passes:", engine.scene().name.c_str(),
                engine.nodeCount(), engine.faceCount(), engine.substepInfo().substeps);
    for (const std::string& pass : engine.pipeline()) std::printf(" %s", pass.c_str());
    std::printf("\n");

    // ---- 4. The host's objects, bound ONCE: the engine restores every binding it changes ----
    GLuint fbo = 0, color = 0, depth = 0, vao = 0;
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kWidth, kHeight);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        std::fprintf(stderr, "framebuffer incomplete\n");
        return 1;
    }
    glViewport(0, 0, kWidth, kHeight);
    glEnable(GL_DEPTH_TEST);
    glClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);

    // The engine's buffers ARE the mesh. Their names never change during the engine's lifetime,
    // so the vertex array is set up once.
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, engine.positionBuffer());
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 16, nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, engine.faceIndexBuffer()); // recorded in the VAO

    const GLuint program = linkProgram();
    glUseProgram(program);
    const glm::mat4 viewProjection =
        glm::perspective(glm::radians(40.0f), float(kWidth) / float(kHeight), 0.05f, 20.0f) *
        glm::lookAt(glm::vec3(1.5f, 1.3f, 2.0f), glm::vec3(0.0f, 0.05f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    glUniformMatrix4fv(glGetUniformLocation(program, "u_viewProjection"), 1, GL_FALSE,
                       glm::value_ptr(viewProjection));
    glUniform1ui(glGetUniformLocation(program, "u_firstClothFace"), engine.bodyFirstFaces()[1]);
    const auto indices = static_cast<GLsizei>(3 * engine.faceCount());

    // ---- 5. The frame loop: simulate, then draw straight from the engine's buffers ----
    int written = 0;
    for (int frame = 0; frame <= frames; ++frame) {
        if (frame > 0) engine.step();
        // step() ended with glMemoryBarrier(VERTEX_ATTRIB_ARRAY | ELEMENT_ARRAY | SHADER_STORAGE):
        // drawing from its buffers needs no barrier of ours. And the state contract says our
        // program, VAO, array/element buffers and framebuffer are still bound; check it here.
        GLint current = 0, boundVao = 0;
        glGetIntegerv(GL_CURRENT_PROGRAM, &current);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &boundVao);
        if (static_cast<GLuint>(current) != program || static_cast<GLuint>(boundVao) != vao) {
            std::fprintf(stderr, "the engine changed the host's bindings\n");
            return 1;
        }
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, nullptr);
        if (frame % 16 == 0) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%03d.ppm", frame);
            const long lit = writePpm(outputDir / name);
            std::printf("frame %3d: wrote %s (%ld pixels not background)\n", frame,
                        (outputDir / name).c_str(), lit);
            ++written;
        }
    }

    // If the host wrote the position buffer itself (say, to drag a node): glBufferSubData needs
    // nothing more, and a compute shader's writes are seen because step() begins with a
    // GL_SHADER_STORAGE_BARRIER_BIT barrier. The face buffer is read-only for the host.

    // ---- 6. Clean up while the context is still current: the host's objects, then the engine ----
    glDeleteProgram(program);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &color);
    glDeleteRenderbuffers(1, &depth);
    return glErrors == 0 && written > 0 ? 0 : 1;
} // ~Engine here: deletes its buffers and programs, puts the previous debug callback back

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path outputDir = argc > 1 ? argv[1] : ".";
    const int frames = argc > 2 ? std::atoi(argv[2]) : 48;
    HostContext host;
    if (!createContext(host)) {
        std::fprintf(stderr, "cannot create an OpenGL 4.3 core context with EGL (error 0x%04X)\n",
                     static_cast<unsigned>(eglGetError()));
        destroyContext(host);
        return 1;
    }
    std::printf("GL: %s | %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                reinterpret_cast<const char*>(glGetString(GL_VERSION)));
    int status = 1;
    try {
        std::filesystem::create_directories(outputDir);
        status = run(outputDir, frames);
    } catch (const std::exception& e) { // glcollide::Error: a bad scene, no GL 4.3, a shader error
        std::fprintf(stderr, "error: %s\n", e.what());
    }
    destroyContext(host);
    return status;
}
