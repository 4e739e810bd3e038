#include "viewer/viewer.hpp"

#include <glcollide/error.hpp>

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

namespace glcollide::viewer {

namespace {

constexpr std::size_t kHistory = 240;         ///< frames in the panel's plots
constexpr double kPickRadius = 20.0;          ///< window pixels: how near the cursor a node is grabbed
constexpr double kRateWindow = 0.5;           ///< s of wall time per frame-rate measurement
constexpr std::size_t kMaxPairLines = 100000; ///< candidate pairs drawn at most (2.4 MB of lines)

/// The pull's spring for a node of mass `nodeMass` pulled in substeps of `h` seconds: the stiffest
/// the explicit pull allows (Engine::setPull takes it explicitly; symplectic Euler is stable while
/// h·sqrt(k/m) < 2), h·sqrt(k/m) = 0.5, times the panel's factor (at most 1), critically damped
/// (c = 2·sqrt(k·m): h·c/m = 1 at most, below the damping's own limit of 2). Cloth springs are stiff,
/// so anything much softer would not move a node against its neighbours.
std::pair<double, double> pullSpring(double nodeMass, double h, double scale) {
    const double k = scale * nodeMass * (0.5 / h) * (0.5 / h);
    return {k, 2.0 * std::sqrt(k * nodeMass)};
}

} // namespace

Loaded openScene(const std::string& path, const std::string& broadPhase) {
    Loaded l;
    l.path = path;
    l.scene = path.empty() ? defaultScene() : loadScene(path);
    // The override is for scenes with collisions; the viewer opens the others as they are.
    const bool collisions =
        l.scene.effects.has(Effect::Collisions) || l.scene.effects.has(Effect::SelfCollisions);
    if (!broadPhase.empty() && collisions) overrideBroadPhase(l.scene, broadPhase);
    l.engine = std::make_unique<Engine>(l.scene);
    for (const std::string& w : l.engine->warnings()) std::cerr << "glcollide: warning: " << w << "\n";
    // The renderer's own framebuffer is for renderFrame only; the viewer draws into the window.
    l.renderer = std::make_unique<render::SceneRenderer>(*l.engine, render::RenderOptions{1, 1, 0, true});
    return l;
}

Viewer::Viewer(Loaded initial, Options options, int framebufferWidth, int framebufferHeight)
    : m_loaded(std::move(initial)), m_options(std::move(options)), m_fbWidth(framebufferWidth),
      m_fbHeight(framebufferHeight) {
    m_clock.scripted = m_options.scripted;
    std::snprintf(m_pathField.data(), m_pathField.size(), "%s", m_loaded.path.c_str());
    resetView();
}

bool Viewer::open(const std::string& path) {
    try {
        Loaded next = openScene(path, m_options.broadPhase);
        releasePull();
        m_loaded = std::move(next);
        m_error.clear();
        std::snprintf(m_pathField.data(), m_pathField.size(), "%s", path.c_str());
        resetView();
        return true;
    } catch (const Error& e) {
        m_error = "could not open " + path + ":\n" + e.what();
        std::cerr << "glcollide: view: " << m_error << "\n";
        return false;
    }
}

void Viewer::restart() {
    // A fresh engine of the same scene; the old one goes first (its buffers are freed). The scene
    // was valid when it was opened, so this fails only as construction on this device can.
    releasePull();
    m_loaded.renderer.reset();
    m_loaded.engine.reset();
    m_loaded.engine = std::make_unique<Engine>(m_loaded.scene);
    m_loaded.renderer =
        std::make_unique<render::SceneRenderer>(*m_loaded.engine, render::RenderOptions{1, 1, 0, m_smooth});
    resetView();
}

void Viewer::resetView() {
    Engine& engine = *m_loaded.engine;
    m_loaded.renderer->setSmooth(m_smooth);
    m_camera.emplace(render::sceneView(engine.scene(), aspect()));
    m_grid = render::sceneGrid(engine.scene());
    m_effects.clear();
    for (Effect e : engine.scene().effects.list()) m_effects.emplace_back(effectName(e));
    m_passNames = engine.pipeline();
    m_passHistory.assign(m_passNames.size(), {});
    m_energyHistory.clear();
    m_clock.pendingSimulated = 0.0;
    afterStateChange();
}

void Viewer::key(int key, int mods) {
    (void)mods;
    switch (key) {
    case GLFW_KEY_SPACE:
        m_clock.playing = !m_clock.playing;
        m_clock.pendingSimulated = 0.0;
        break;
    case GLFW_KEY_N:
    case GLFW_KEY_RIGHT:
        // One frame (or the rest of the frame that single substeps began: Engine::step finishes it).
        m_clock.playing = false;
        stepEngine();
        break;
    case GLFW_KEY_PERIOD:
        // One substep (Engine::stepSubstep); S is smooth shading.
        m_clock.playing = false;
        stepSubstep();
        break;
    case GLFW_KEY_R:
        restart();
        break;
    case GLFW_KEY_F:
        frameAll();
        break;
    case GLFW_KEY_W:
        m_wireframe = !m_wireframe;
        break;
    case GLFW_KEY_I:
        m_showIntersecting = !m_showIntersecting;
        afterStateChange();
        break;
    case GLFW_KEY_P:
        m_pinned = !m_pinned;
        break;
    case GLFW_KEY_C:
        m_showPairs = !m_showPairs;
        afterStateChange();
        break;
    case GLFW_KEY_B:
        m_showBoxes = !m_showBoxes;
        afterStateChange();
        break;
    case GLFW_KEY_MINUS: // the boxes one level up the tree
        m_boxDepth = std::max(m_boxDepth - 1, 0);
        afterStateChange();
        break;
    case GLFW_KEY_EQUAL: // one level down (clamped to the tree's depth when drawn)
        m_boxDepth = m_boxDepth + 1;
        afterStateChange();
        break;
    case GLFW_KEY_K:
        m_showContacts = !m_showContacts;
        afterStateChange();
        break;
    case GLFW_KEY_S:
        m_smooth = !m_smooth;
        m_loaded.renderer->setSmooth(m_smooth);
        break;
    case GLFW_KEY_H:
        m_panel = !m_panel;
        break;
    case GLFW_KEY_LEFT_BRACKET: // slower: halve the speed, down to 1/64
        m_clock.speed = std::max(m_clock.speed / 2.0, 1.0 / 64.0);
        break;
    case GLFW_KEY_RIGHT_BRACKET: // faster: double it, up to real time
        m_clock.speed = std::min(m_clock.speed * 2.0, 1.0);
        break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        m_quit = true;
        break;
    default:
        break;
    }
}

void Viewer::mouseDown(int button, int mods, double x, double y) {
    m_dragButton = button;
    m_dragMods = mods;
    m_lastX = x;
    m_lastY = y;
    // Ctrl + left button grabs the node nearest the cursor (MuJoCo: Ctrl + right).
    if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_CONTROL)) {
        const std::optional<std::uint32_t> node = pick(x, y);
        if (!node) return;
        const std::vector<glm::dvec3> positions = m_loaded.engine->readPositions();
        Grab g;
        g.node = *node;
        g.planePoint = positions[*node];
        g.target = g.planePoint;
        m_grab = g;
        updatePull();
    }
}

void Viewer::mouseMove(double x, double y) {
    const double dx = x - m_lastX, dy = y - m_lastY;
    m_lastX = x;
    m_lastY = y;
    if (m_dragButton < 0) return;
    if (m_grab) {
        // The target: where the cursor's ray meets the plane through the grabbed point facing the eye.
        const glm::dvec3 eye = m_camera->eye();
        const glm::dvec3 normal = glm::normalize(m_camera->target() - eye);
        const glm::dvec3 ray = cursorRay(x, y);
        const double along = glm::dot(ray, normal);
        // A ray along the plane (|cos| <= 1e-9: the cursor 90° off the view direction, which a
        // perspective view never shows) keeps the last target.
        if (std::abs(along) > 1e-9)
            m_grab->target = eye + ray * (glm::dot(m_grab->planePoint - eye, normal) / along);
        updatePull();
        return;
    }
    const double pixelsPerWindowPixel = static_cast<double>(m_fbHeight) / std::max(m_winHeight, 1);
    if (m_dragButton == GLFW_MOUSE_BUTTON_LEFT && !(m_dragMods & GLFW_MOD_SHIFT))
        m_camera->orbit(dx, dy);
    else // right or middle button, or Shift + left: pan
        m_camera->pan(dx * pixelsPerWindowPixel, dy * pixelsPerWindowPixel, m_fbHeight);
}

void Viewer::mouseUp(int button) {
    if (button != m_dragButton) return;
    m_dragButton = -1;
    releasePull();
}

void Viewer::scroll(double steps) {
    m_camera->zoom(steps);
}

void Viewer::releasePull() {
    if (!m_grab) return;
    if (m_loaded.engine) {
        const glm::dvec3 x = m_loaded.engine->readPositions()[m_grab->node];
        char line[200];
        std::snprintf(
            line, sizeof line,
            "pull: node %u released: %.4f m from the target where it was grabbed, %.4f m at the release",
            m_grab->node, glm::length(m_grab->target - m_grab->planePoint), glm::length(m_grab->target - x));
        m_pullLog.emplace_back(line);
        m_loaded.engine->setPull(std::nullopt);
    }
    m_grab.reset();
}

void Viewer::updatePull() {
    if (!m_grab) return;
    Engine& engine = *m_loaded.engine;
    // The node's mass, from the scene (global node = body's first node + local).
    const std::vector<std::uint32_t> first = engine.bodyFirstNodes();
    std::size_t body = 0;
    while (body + 1 < first.size() && first[body + 1] <= m_grab->node) ++body;
    const Body& b = engine.scene().bodies[body];
    const double nodeMass = b.masses[m_grab->node - first[body]];
    const auto [k, c] = pullSpring(nodeMass, engine.substepInfo().substepLength, m_pullScale);
    m_grab->stiffness = k;
    m_grab->damping = c;
    engine.setPull(NodePull{m_grab->node, m_grab->target, k, c});
}

std::optional<std::uint32_t> Viewer::pick(double x, double y) const {
    const Engine& engine = *m_loaded.engine;
    const std::vector<glm::dvec3> positions = engine.readPositions();
    const render::View view = currentView();
    const double px = x * m_fbWidth / std::max(m_winWidth, 1), py = y * m_fbHeight / std::max(m_winHeight, 1);
    const double radius = kPickRadius * m_fbHeight / std::max(m_winHeight, 1);
    // Pinned nodes cannot be pulled: the free nodes of each body.
    std::vector<std::uint8_t> pinned;
    for (const Body& b : engine.scene().bodies) pinned.insert(pinned.end(), b.pinned.begin(), b.pinned.end());
    std::optional<std::uint32_t> best;
    double bestDepth = std::numeric_limits<double>::infinity();
    for (std::uint32_t i = 0; i < positions.size(); ++i) {
        if (i < pinned.size() && pinned[i]) continue;
        if (!view.inFront(positions[i])) continue;
        const glm::dvec3 p = view.project(positions[i], m_fbWidth, m_fbHeight);
        if (std::hypot(p.x - px, p.y - py) > radius) continue;
        // Among the nodes near the cursor, the one nearest the eye: the surface the user sees.
        if (p.z < bestDepth) {
            bestDepth = p.z;
            best = i;
        }
    }
    return best;
}

glm::dvec3 Viewer::cursorRay(double x, double y) const {
    const render::View view = currentView();
    const glm::dmat4 inverse = glm::inverse(view.viewProjection());
    const double ndcX = 2.0 * x / std::max(m_winWidth, 1) - 1.0,
                 ndcY = 1.0 - 2.0 * y / std::max(m_winHeight, 1);
    const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
    const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    return glm::normalize(glm::dvec3(farPoint) / farPoint.w - glm::dvec3(nearPoint) / nearPoint.w);
}

double Viewer::aspect() const {
    return static_cast<double>(std::max(m_fbWidth, 1)) / std::max(m_fbHeight, 1);
}

render::View Viewer::currentView() const {
    const double sceneRadius = glm::length(m_grid.centre - m_camera->target()) + 1.5 * m_grid.halfSize;
    return m_camera->view(aspect(), sceneRadius);
}

void Viewer::frameAll() {
    const std::vector<glm::dvec3> x = m_loaded.engine->readPositions();
    if (x.empty()) return;
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& p : x) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    m_camera->frame(lo, hi, aspect());
}

void Viewer::stepEngine() {
    Engine& engine = *m_loaded.engine;
    engine.step();
    ++m_simulatedFrames;
    m_clock.windowSimulated += engine.scene().time.dt;
    const StepStats& s = engine.lastStep();
    for (std::size_t p = 0; p < m_passHistory.size() && p < s.passes.size(); ++p) {
        m_passHistory[p].push_back(static_cast<float>(s.passes[p].gpuMilliseconds));
        if (m_passHistory[p].size() > kHistory) m_passHistory[p].pop_front();
    }
    afterStateChange();
}

void Viewer::stepSubstep() {
    Engine& engine = *m_loaded.engine;
    engine.stepSubstep();
    m_clock.windowSimulated += engine.substepInfo().substepLength;
    const StepStats& s = engine.lastStep();
    if (s.substepInFrame == 0) { // this substep ended a frame: its timings are the frame's
        ++m_simulatedFrames;
        for (std::size_t p = 0; p < m_passHistory.size() && p < s.passes.size(); ++p) {
            m_passHistory[p].push_back(static_cast<float>(s.passes[p].gpuMilliseconds));
            if (m_passHistory[p].size() > kHistory) m_passHistory[p].pop_front();
        }
    }
    afterStateChange();
}

void Viewer::afterStateChange() {
    Engine& engine = *m_loaded.engine;
    m_energy = engine.energy();
    m_energyHistory.push_back(static_cast<float>(m_energy->total()));
    if (m_energyHistory.size() > kHistory) m_energyHistory.pop_front();
    m_intersecting.clear();
    m_pairLines.clear();
    m_contactLines.clear();
    m_boxLines.clear();
    m_boxNote.clear();
    const EffectSet& effects = engine.scene().effects;
    if (!(effects.has(Effect::Collisions) || effects.has(Effect::SelfCollisions))) return;
    if (!m_showIntersecting && !m_showPairs && !m_showContacts && !m_showBoxes) return;
    // As `render` does: detect on the drawn positions, so red faces and pairs are this state's.
    engine.detectCollisions();
    if (m_showIntersecting) m_intersecting = engine.readIntersectingPairs();
    if (m_showBoxes) {
        // The broad phase's boxes at the chosen depth (clamped to the tree's), their 12 edges each.
        try {
            m_boxMaxDepth = engine.broadPhaseDepth();
            m_boxDepth = std::min(m_boxDepth, m_boxMaxDepth);
            for (const BroadPhaseBox& b : engine.readBroadPhaseBoxes(m_boxDepth)) {
                if (m_boxLines.size() + 12 > kMaxPairLines) break;
                const auto corner = [&](int k) {
                    return glm::vec3(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y,
                                     k & 4 ? b.hi.z : b.lo.z);
                };
                for (int k = 0; k < 8; ++k)
                    for (const int bit : {1, 2, 4})
                        if (!(k & bit)) m_boxLines.push_back({corner(k), corner(k | bit)});
            }
        } catch (const Error& e) {
            m_boxNote = e.what(); // e.g. the all-pairs broad phase keeps no boxes
        }
    }
    if (m_showContacts) {
        // Feature contacts as lines between their closest points (side A's to side B's).
        const std::vector<glm::dvec3> x = engine.readPositions();
        for (const FeatureContact& c : engine.readContacts()) {
            if (m_contactLines.size() >= kMaxPairLines) break;
            glm::dvec3 a(0.0), b(0.0);
            for (int k = 0; k < 4; ++k) {
                a += std::max(c.weights[k], 0.0) * x[c.nodes[k]];
                b += std::max(-c.weights[k], 0.0) * x[c.nodes[k]];
            }
            m_contactLines.push_back({glm::vec3(a), glm::vec3(b)});
        }
    }
    if (!m_showPairs) return;
    // Candidate pairs (faces within the contact thickness) as lines between the faces' centroids.
    const std::vector<std::array<std::uint32_t, 2>> pairs = engine.readCandidatePairs();
    const std::vector<glm::dvec3> x = engine.readPositions();
    const std::vector<std::uint32_t> firstNodes = engine.bodyFirstNodes();
    std::vector<glm::vec3> centroids;
    centroids.reserve(engine.faceCount());
    for (std::size_t b = 0; b < engine.scene().bodies.size(); ++b)
        for (const auto& f : engine.scene().bodies[b].faces)
            centroids.emplace_back(
                (x[firstNodes[b] + f[0]] + x[firstNodes[b] + f[1]] + x[firstNodes[b] + f[2]]) / 3.0);
    for (const auto& p : pairs) {
        if (m_pairLines.size() >= kMaxPairLines) break;
        if (p[0] < centroids.size() && p[1] < centroids.size())
            m_pairLines.push_back({centroids[p[0]], centroids[p[1]]});
    }
}

void Viewer::frame(double wallSeconds, int framebufferWidth, int framebufferHeight, int windowWidth,
                   int windowHeight) {
    m_fbWidth = framebufferWidth;
    m_fbHeight = framebufferHeight;
    m_winWidth = windowWidth;
    m_winHeight = windowHeight;
    Clock& c = m_clock;
    if (c.shownFrames == 0) c.windowStart = wallSeconds;
    ++c.shownFrames;
    ++c.windowFrames;
    const double dt = m_loaded.engine->scene().time.dt;
    if (c.playing) {
        if (c.scripted) {
            // Deterministic: one engine frame per shown frame, every (1/speed)-th frame in slow motion.
            const auto every = static_cast<std::uint64_t>(std::llround(1.0 / c.speed));
            if (c.shownFrames % every == 0) stepEngine();
        } else {
            // Real time (times the speed) as far as the engine keeps up; at most one engine frame
            // per shown frame, and no debt carried beyond one frame, so the viewer stays responsive.
            c.pendingSimulated = std::min(c.pendingSimulated + (wallSeconds - m_lastWall) * c.speed, dt);
            // Relative 1e-9: summed wall-time steps that should make exactly dt may round below it.
            if (c.pendingSimulated >= dt * (1.0 - 1e-9)) {
                c.pendingSimulated -= dt;
                stepEngine();
            }
        }
    }
    m_lastWall = wallSeconds;
    if (wallSeconds - c.windowStart >= kRateWindow) {
        const double span = wallSeconds - c.windowStart;
        c.framesPerSecond = static_cast<double>(c.windowFrames) / span;
        c.simulatedRatio = c.windowSimulated / span;
        c.windowStart = wallSeconds;
        c.windowFrames = 0;
        c.windowSimulated = 0.0;
    }

    render::SceneRenderer& renderer = *m_loaded.renderer;
    renderer.setView(currentView());
    render::Overlays overlays;
    overlays.wireframe = m_wireframe;
    overlays.pinnedNodes = m_pinned;
    if (m_grab) overlays.segment = {{m_loaded.engine->readPositions()[m_grab->node], m_grab->target}};
    overlays.pairLines = m_pairLines;
    overlays.contactLines = m_contactLines;
    overlays.boxLines = m_boxLines;
    renderer.draw(*m_loaded.engine, m_intersecting, {0, framebufferWidth, framebufferHeight}, overlays);
}

std::vector<std::string> Viewer::summary() const {
    std::vector<std::string> lines = m_pullLog;
    const Engine& engine = *m_loaded.engine;
    char line[300];
    std::snprintf(line, sizeof line,
                  "view: %s: %llu frames shown, %llu simulated (this scene at t = %.4f s, frame %llu)",
                  engine.scene().name.c_str(), static_cast<unsigned long long>(m_clock.shownFrames),
                  static_cast<unsigned long long>(m_simulatedFrames), engine.lastStep().time,
                  static_cast<unsigned long long>(engine.lastStep().frame));
    lines.emplace_back(line);
    return lines;
}

} // namespace glcollide::viewer
