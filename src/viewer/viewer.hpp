#pragma once
// `glcollide view`: the state of the viewer and what its inputs do. The engine runs in the
// window's own GL context through the public embedding API (docs/embedding.md); the renderer
// (render::SceneRenderer) draws its position and face buffers straight into the window. The
// window, the main loop and the panel's toolkit are in view_command.cpp and panel.cpp.

#include "render/scene_renderer.hpp"
#include "viewer/orbit_camera.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glcollide::viewer {

/// What a scene loads into: the engine and its renderer (made together, replaced together).
struct Loaded {
    std::string path; ///< empty: the built-in default scene
    Scene scene;
    std::unique_ptr<Engine> engine;
    std::unique_ptr<render::SceneRenderer> renderer;
};

/// Loads a scene file (empty: the built-in default scene), applies the broad-phase override (to a
/// scene with collisions) and
/// builds its engine and renderer on the current context. Throws Error as loadScene and Engine do.
Loaded openScene(const std::string& path, const std::string& broadPhase);

/// The viewer's time control and its measured rates.
struct Clock {
    bool playing = true;
    double speed = 1.0;            ///< simulated seconds per wall second (slow motion < 1)
    bool scripted = false;         ///< --frames: one engine frame per shown frame while playing
    double pendingSimulated = 0.0; ///< s: simulated time owed to the wall clock (interactive)
    std::uint64_t shownFrames = 0;
    // Rates over the last half second.
    double windowStart = 0.0, windowSimulated = 0.0;
    std::uint64_t windowFrames = 0;
    double framesPerSecond = 0.0, simulatedRatio = 0.0;
};

/// A node held by the mouse: the engine pulls it towards the point under the cursor in the plane
/// through the node facing the camera (Engine::setPull).
struct Grab {
    std::uint32_t node = 0;
    glm::dvec3 planePoint{0.0}; ///< the node where it was grabbed
    glm::dvec3 target{0.0};     ///< m: the point under the cursor
    double stiffness = 0.0, damping = 0.0;
};

class Viewer {
  public:
    struct Options {
        std::string broadPhase; ///< applied to every scene opened
        bool scripted = false;  ///< --frames: deterministic time (one engine frame per shown frame)
    };
    Viewer(Loaded initial, Options options, int framebufferWidth, int framebufferHeight);

    /// Opens another scene; on failure keeps the current one and shows the error in the panel
    /// (also printed on stderr). Returns whether it opened.
    bool open(const std::string& path);
    /// The current scene again from its start (a fresh engine).
    void restart();

    // Input, in window pixels from the top left (the cursor) and GLFW codes.
    void key(int key, int mods);
    void mouseDown(int button, int mods, double x, double y);
    void mouseMove(double x, double y);
    void mouseUp(int button);
    void scroll(double steps);

    /// Advances time for one shown frame (`wallSeconds`: now, on a monotonic clock) and draws the
    /// scene into the window's framebuffer of this size (the panel is drawn after it).
    void frame(double wallSeconds, int framebufferWidth, int framebufferHeight, int windowWidth,
               int windowHeight);
    /// The panel (Dear ImGui), between the toolkit's NewFrame and Render.
    void panel();

    [[nodiscard]] bool quitRequested() const { return m_quit; }
    [[nodiscard]] const Loaded& loaded() const { return m_loaded; }
    [[nodiscard]] const Clock& clock() const { return m_clock; }
    /// Lines for stdout at exit: what was shown and simulated, pulls released.
    [[nodiscard]] std::vector<std::string> summary() const;

  private:
    void resetView(); ///< camera, panel data and overlays for the engine now loaded
    void stepEngine();
    void stepSubstep();      ///< one substep (Engine::stepSubstep), key '.'
    void afterStateChange(); ///< the overlays' data (intersecting pairs) for the state now drawn
    void frameAll();
    void updatePull();
    std::optional<std::uint32_t> pick(double x, double y) const;
    [[nodiscard]] glm::dvec3 cursorRay(double x, double y) const; ///< unit direction from the eye
    [[nodiscard]] double aspect() const;
    [[nodiscard]] render::View currentView() const;
    void releasePull();

    Loaded m_loaded;
    Options m_options;
    std::optional<OrbitCamera> m_camera;
    render::Grid m_grid;
    Clock m_clock;
    bool m_quit = false;

    // Overlays and shading.
    bool m_showIntersecting = true, m_wireframe = false, m_pinned = false, m_smooth = true, m_panel = true;
    std::vector<std::array<std::uint32_t, 2>> m_intersecting;
    bool m_showPairs = false;                          ///< candidate face pairs as lines (key C)
    std::vector<std::array<glm::vec3, 2>> m_pairLines; ///< centroid to centroid, at most kMaxPairLines
    bool m_showContacts = false;                       ///< feature contacts as lines (key K)
    bool m_showBoxes = false; ///< the broad phase's boxes (key B) at m_boxDepth (keys - and =)
    int m_boxDepth = 1, m_boxMaxDepth = 0;
    std::string m_boxNote; ///< why no boxes are drawn (the engine's error), empty otherwise
    std::vector<std::array<glm::vec3, 2>> m_boxLines; ///< 12 edges per box, at most kMaxPairLines
    std::vector<std::array<glm::vec3, 2>>
        m_contactLines; ///< closest point to closest point, at most kMaxPairLines

    // The mouse.
    int m_fbWidth = 1, m_fbHeight = 1, m_winWidth = 1, m_winHeight = 1;
    int m_dragButton = -1, m_dragMods = 0;
    double m_lastX = 0.0, m_lastY = 0.0;
    std::optional<Grab> m_grab;
    double m_pullScale = 1.0; ///< the panel's factor on the pull's stiffness
    std::vector<std::string> m_pullLog;

    // The panel's data.
    std::string m_error;
    std::array<char, 1024> m_pathField{};
    std::vector<std::string> m_effects;
    std::vector<std::string> m_passNames;
    std::vector<std::deque<float>> m_passHistory; ///< ms per pass, the last kHistory frames
    std::deque<float> m_energyHistory;
    std::optional<EnergyReport> m_energy;
    std::uint64_t m_simulatedFrames = 0; ///< engine frames since the viewer started (all scenes)
    double m_lastWall = 0.0;             ///< s: the last frame's wall time
};

} // namespace glcollide::viewer
