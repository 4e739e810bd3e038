// glcollide view: a GLFW window with an OpenGL 4.3 core context in which the engine runs, drawn by
// render::SceneRenderer from the engine's own buffers, with a Dear ImGui panel (docs/viewer.md).
#include "app/commands.hpp"
#include "render/scene_renderer.hpp"
#include "viewer/input_script.hpp"
#include "viewer/viewer.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <epoxy/gl.h>
// After epoxy: GLFW must not include a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

namespace glcollide::app {
namespace {

std::string g_glfwError; ///< GLFW's last error message (its callback has no user pointer)

void onGlfwError(int code, const char* message) {
    char text[512];
    std::snprintf(text, sizeof text, "%s (GLFW error 0x%X)", message ? message : "unknown error",
                  static_cast<unsigned>(code));
    g_glfwError = text;
}

/// A clear error when there is no window system to talk to, before GLFW tries.
void requireDisplay() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((x11 == nullptr || *x11 == '\0') && (wayland == nullptr || *wayland == '\0'))
        throw Error("no display: DISPLAY is not set; view needs a window system (try xvfb-run -a glcollide "
                    "view ...); "
                    "run and render need none");
}

/// GLFW and, once made, the window and the panel's toolkit, torn down in reverse order.
struct Window {
    GLFWwindow* handle = nullptr;
    bool imgui = false;
    ~Window() {
        if (imgui) {
            ImGui_ImplOpenGL3_Shutdown();
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
        if (handle) glfwDestroyWindow(handle);
        glfwTerminate();
    }
};

/// What the window's callbacks reach (GLFW gives them the window's user pointer only).
struct Callbacks {
    viewer::Viewer* viewer = nullptr;
    bool userInput = true; ///< false with --frames: only the input script drives the viewer
    /// An exception thrown inside a callback: it must not cross GLFW's C code, so it waits here
    /// and is rethrown after glfwPollEvents returns.
    std::exception_ptr pending;
};

Callbacks* callbacksOf(GLFWwindow* window) {
    return static_cast<Callbacks*>(glfwGetWindowUserPointer(window));
}

/// Runs `f` on the viewer when real input is on, keeping any exception for after the event loop.
template <typename F> void guarded(GLFWwindow* w, F&& f) {
    Callbacks* c = callbacksOf(w);
    if (!c->viewer || !c->userInput || c->pending) return;
    try {
        f(*c->viewer);
    } catch (...) {
        c->pending = std::current_exception();
    }
}

// Real input goes to the scene unless the panel has it (the toolkit chains to these callbacks).
void onKey(GLFWwindow* w, int key, int /*scancode*/, int action, int mods) {
    if (action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
    guarded(w, [&](viewer::Viewer& v) { v.key(key, mods); });
}
void onMouseButton(GLFWwindow* w, int button, int action, int mods) {
    double x = 0, y = 0;
    glfwGetCursorPos(w, &x, &y);
    guarded(w, [&](viewer::Viewer& v) {
        if (action == GLFW_RELEASE)
            v.mouseUp(button); // always: a drag that began in the scene ends there
        else if (!ImGui::GetIO().WantCaptureMouse)
            v.mouseDown(button, mods, x, y);
    });
}
void onCursor(GLFWwindow* w, double x, double y) {
    guarded(w, [&](viewer::Viewer& v) { v.mouseMove(x, y); });
}
void onScroll(GLFWwindow* w, double /*dx*/, double dy) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    guarded(w, [&](viewer::Viewer& v) { v.scroll(dy); });
}
void onDrop(GLFWwindow* w, int count, const char** paths) {
    if (count > 0) guarded(w, [&](viewer::Viewer& v) { v.open(paths[0]); });
}

void writeScreenshot(const std::string& path, int width, int height) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK); // what the window shows once this frame is swapped in
    render::writePng(path, render::readPixels(width, height));
    std::cout << "view: wrote " << path << " (" << width << "x" << height << ")\n";
}

void apply(viewer::Viewer& v, const viewer::InputEvent& e) {
    using Kind = viewer::InputEvent::Kind;
    switch (e.kind) {
    case Kind::Key:
        v.key(e.key, e.mods);
        break;
    case Kind::MouseDown:
        v.mouseMove(e.x, e.y);
        v.mouseDown(e.button, e.mods, e.x, e.y);
        break;
    case Kind::MouseMove:
        v.mouseMove(e.x, e.y);
        break;
    case Kind::MouseUp:
        v.mouseUp(e.button);
        break;
    case Kind::Scroll:
        v.scroll(e.scroll);
        break;
    case Kind::Open:
        v.open(e.path);
        break;
    case Kind::Screenshot:
        break; // after the frame is drawn
    }
}

} // namespace

int viewCommand(const ViewOptions& o) {
    const auto [width, height] = parseSize(o.size);
    if (o.frames && *o.frames <= 0) throw Error("--frames must be positive");
    if (!o.screenshot.empty() && !o.frames) throw Error("--screenshot needs --frames N (it writes frame N)");
    // A window's context comes from the window system, not from an EGL device: only Mesa's
    // software renderer can be asked for (LIBGL_ALWAYS_SOFTWARE, read by Mesa's GLX and EGL).
    if (o.device == "software")
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    else if (!o.device.empty() && o.device != "auto")
        throw Error("view --device: a window's GL context comes from the window system, so only auto and "
                    "software can be chosen (got '" +
                    o.device + "')");
    // Everything that can be checked without a window is checked first.
    std::vector<viewer::InputEvent> events;
    if (!o.input.empty()) events = viewer::readInputScript(o.input, o.frames.value_or(0), width, height);
    if (!o.scenePath.empty()) (void)loadScene(o.scenePath); // a bad scene: its error, no window
    if (!o.broadPhase.empty() && !broadPhaseFromName(o.broadPhase))
        throw Error("--broad-phase: unknown broad phase \"" + o.broadPhase +
                    "\"; expected octree, masked, all_pairs or bvh");

    requireDisplay();
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit())
        throw Error("cannot connect to the window system (DISPLAY=" +
                    std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") + "): " + g_glfwError +
                    "; view needs a window system (try xvfb-run)");
    Window window;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 4);
    window.handle = glfwCreateWindow(width, height, "glcollide view", nullptr, nullptr);
    if (window.handle == nullptr)
        throw Error("cannot create a window with an OpenGL 4.3 core context: " + g_glfwError);
    glfwMakeContextCurrent(window.handle);
    glfwSwapInterval(o.frames ? 0 : 1); // no user: as fast as it goes; a user: the display's rate

    Callbacks callbacks;
    callbacks.userInput = !o.frames;
    glfwSetWindowUserPointer(window.handle, &callbacks);
    // Ours first: the toolkit's backend installs its own and chains to these.
    glfwSetKeyCallback(window.handle, onKey);
    glfwSetMouseButtonCallback(window.handle, onMouseButton);
    glfwSetCursorPosCallback(window.handle, onCursor);
    glfwSetScrollCallback(window.handle, onScroll);
    glfwSetDropCallback(window.handle, onDrop);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    window.imgui = true;
    ImGui::GetIO().IniFilename = nullptr; // write no imgui.ini into the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window.handle, true);
    ImGui_ImplOpenGL3_Init("#version 430 core");

    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window.handle, &fbWidth, &fbHeight);
    std::optional<viewer::Viewer> view;
    view.emplace(viewer::openScene(o.scenePath, o.broadPhase),
                 viewer::Viewer::Options{o.broadPhase, o.frames.has_value()}, fbWidth, fbHeight);
    callbacks.viewer = &*view;
    std::cout << "view: " << view->loaded().engine->scene().name << " on "
              << reinterpret_cast<const char*>(glGetString(GL_RENDERER)) << " ("
              << reinterpret_cast<const char*>(glGetString(GL_VERSION)) << ")\n";

    std::size_t next = 0;
    for (int shown = 1; !glfwWindowShouldClose(window.handle) && !view->quitRequested(); ++shown) {
        glfwPollEvents();
        if (callbacks.pending) std::rethrow_exception(callbacks.pending);
        for (; next < events.size() && events[next].frame == shown; ++next) apply(*view, events[next]);
        int winWidth = 0, winHeight = 0;
        glfwGetFramebufferSize(window.handle, &fbWidth, &fbHeight);
        glfwGetWindowSize(window.handle, &winWidth, &winHeight);
        view->frame(glfwGetTime(), fbWidth, fbHeight, winWidth, winHeight);
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        view->panel();
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        for (const viewer::InputEvent& e : events)
            if (e.frame == shown && e.kind == viewer::InputEvent::Kind::Screenshot)
                writeScreenshot(e.path, fbWidth, fbHeight);
        if (o.frames && shown == *o.frames) {
            if (!o.screenshot.empty()) writeScreenshot(o.screenshot, fbWidth, fbHeight);
            break;
        }
        glfwSwapBuffers(window.handle);
    }
    for (const std::string& line : view->summary()) std::cout << line << "\n";
    callbacks.viewer = nullptr;
    view.reset(); // the engine and renderer go while their context is current
    return 0;
}

} // namespace glcollide::app
