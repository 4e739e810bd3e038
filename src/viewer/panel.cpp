// The viewer's panel (Dear ImGui): the scene, time control, overlays, what the engine reports.
#include "viewer/viewer.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace glcollide::viewer {
namespace {

void plot(const char* label, const std::deque<float>& values, const char* overlay) {
    std::vector<float> v(values.begin(), values.end());
    if (v.empty()) v.push_back(0.0f);
    ImGui::PlotLines(label, v.data(), static_cast<int>(v.size()), 0, overlay, 0.0f, FLT_MAX, ImVec2(0, 36));
}

void wrappedList(const char* title, const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& i : items) text += (text.empty() ? "" : " ") + i;
    ImGui::TextWrapped("%s: %s", title, text.empty() ? "(none)" : text.c_str());
}

} // namespace

void Viewer::panel() {
    if (!m_panel) return;
    const Engine& engine = *m_loaded.engine;
    const StepStats& s = engine.lastStep();
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(360, static_cast<float>(std::max(m_winHeight - 16, 100))),
                             ImGuiCond_Once);
    ImGui::Begin("glcollide view");

    ImGui::TextWrapped("%s", engine.scene().name.c_str());
    ImGui::InputText("##path", m_pathField.data(), m_pathField.size());
    ImGui::SameLine();
    if (ImGui::Button("Open")) open(m_pathField.data());
    ImGui::TextDisabled("or drop a scene file on the window");
    if (!m_error.empty()) ImGui::TextColored(ImVec4(0.95f, 0.3f, 0.3f, 1.0f), "%s", m_error.c_str());

    if (ImGui::CollapsingHeader("Time", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (ImGui::Button(m_clock.playing ? "Pause (space)" : "Play (space)")) key(GLFW_KEY_SPACE, 0);
        ImGui::SameLine();
        if (ImGui::Button("Frame (N)")) key(GLFW_KEY_N, 0);
        ImGui::SameLine();
        if (ImGui::Button("Substep (.)")) key(GLFW_KEY_PERIOD, 0);
        ImGui::SameLine();
        if (ImGui::Button("Restart (R)")) key(GLFW_KEY_R, 0);
        float speed = static_cast<float>(m_clock.speed);
        if (ImGui::SliderFloat("speed", &speed, 1.0f / 64.0f, 1.0f, "%.3f x", ImGuiSliderFlags_Logarithmic))
            m_clock.speed = speed;
        ImGui::Text("frame %llu, t = %.4f s (dt %.4g s)", static_cast<unsigned long long>(s.frame), s.time,
                    engine.scene().time.dt);
        if (s.substepInFrame > 0)
            ImGui::Text("mid-frame: substep %d of %d done", s.substepInFrame, engine.substepInfo().substeps);
        ImGui::Text("%.1f frames/s shown, simulated/wall time %.3f", m_clock.framesPerSecond,
                    m_clock.simulatedRatio);
        const SubstepInfo& sub = engine.substepInfo();
        ImGui::Text("substeps %d per frame (%s), h = %.3g s", sub.substeps, sub.automatic ? "auto" : "scene",
                    sub.substepLength);
        ImGui::Text("step() %.2f ms wall, %.1f dispatches/substep", s.wallMilliseconds,
                    s.dispatchesPerSubstep);
    }

    if (ImGui::CollapsingHeader("Overlays", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (ImGui::Checkbox("intersecting faces, red (I)", &m_showIntersecting)) afterStateChange();
        ImGui::Checkbox("wireframe (W)", &m_wireframe);
        ImGui::Checkbox("pinned nodes (P)", &m_pinned);
        if (ImGui::Checkbox("smooth shading (S)", &m_smooth)) m_loaded.renderer->setSmooth(m_smooth);
        if (ImGui::Checkbox("candidate face pairs, green (C)", &m_showPairs)) afterStateChange();
        if (ImGui::Checkbox("feature contacts, cyan (K)", &m_showContacts)) afterStateChange();
        if (ImGui::Checkbox("broad-phase boxes, violet (B)", &m_showBoxes)) afterStateChange();
        if (m_showBoxes) {
            if (ImGui::SliderInt("box depth (- =)", &m_boxDepth, 0, std::max(m_boxMaxDepth, 0)))
                afterStateChange();
            if (!m_boxNote.empty())
                ImGui::TextWrapped("%s", m_boxNote.c_str());
            else
                ImGui::Text("boxes drawn %zu", m_boxLines.size() / 12);
        }
        float pull = static_cast<float>(m_pullScale);
        if (ImGui::SliderFloat("pull", &pull, 0.01f, 1.0f, "%.2f x", ImGuiSliderFlags_Logarithmic))
            m_pullScale = pull;
        if (m_grab)
            ImGui::Text("pulling node %u: k %.3g N/m, c %.3g N s/m", m_grab->node, m_grab->stiffness,
                        m_grab->damping);
        else
            ImGui::TextDisabled("Ctrl + left drag on a body pulls a node");
    }

    if (ImGui::CollapsingHeader("Scene and pipeline", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("%zu bodies, %u nodes, %u faces, %u springs", engine.scene().bodies.size(),
                    engine.nodeCount(), engine.faceCount(), engine.springCount());
        wrappedList("effects", m_effects);
        wrappedList("pipeline", m_passNames);
        if (engine.scene().effects.has(Effect::Collisions) ||
            engine.scene().effects.has(Effect::SelfCollisions))
            ImGui::Text("broad phase: %s", broadPhaseName(engine.scene().collision.broadPhase));
    }

    if (ImGui::CollapsingHeader("GPU time per pass", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (std::size_t p = 0; p < m_passNames.size() && p < m_passHistory.size(); ++p) {
            char overlay[64];
            std::snprintf(overlay, sizeof overlay, "%.3f ms",
                          m_passHistory[p].empty() ? 0.0 : static_cast<double>(m_passHistory[p].back()));
            plot(m_passNames[p].c_str(), m_passHistory[p], overlay);
        }
    }

    if (ImGui::CollapsingHeader("Energy, collisions, solver", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (m_energy) {
            ImGui::Text("kinetic %.4g J, potential %.4g J", m_energy->kinetic, m_energy->potential);
            if (m_energy->contact != 0.0) ImGui::Text("contact %.4g J", m_energy->contact);
            char overlay[64];
            std::snprintf(overlay, sizeof overlay, "total %.5g J", m_energy->total());
            plot("energy", m_energyHistory, overlay);
        }
        if (m_showPairs) ImGui::Text("candidate pairs drawn %zu", m_pairLines.size());
        if (m_showContacts) ImGui::Text("feature contacts drawn %zu", m_contactLines.size());
        if (s.collisions) {
            const CollisionStats& c = s.collision;
            ImGui::Text("candidates %u, contacts %u", c.candidatePairs, c.contacts);
            ImGui::Text("intersecting pairs %u (frame max %u), drawn %zu", c.intersectingPairs,
                        c.maxIntersectingPairs, m_intersecting.size());
            if (c.boxPairs) ImGui::Text("octree box pairs %u", c.boxPairs);
            if (c.bvhNodeVisits) ImGui::Text("BVH node visits %u", c.bvhNodeVisits);
        } else if (engine.scene().effects.has(Effect::Collisions) ||
                   engine.scene().effects.has(Effect::SelfCollisions)) {
            ImGui::TextDisabled("collision counts: after the first frame");
        } else {
            ImGui::TextDisabled("no collision effect");
        }
        if (s.solver.implicit)
            ImGui::Text("CG iterations: max %u, total %u, residual %.2g%s", s.solver.maxIterations,
                        s.solver.totalIterations, s.solver.maxRelativeResidual,
                        s.solver.unconvergedSubsteps ? " (unconverged)" : "");
        else
            ImGui::TextDisabled("symplectic Euler: no solver iterations");
        if (s.nonFinite.found)
            ImGui::TextColored(ImVec4(0.95f, 0.3f, 0.3f, 1.0f), "non-finite state at frame %llu, node %u",
                               static_cast<unsigned long long>(s.nonFinite.frame), s.nonFinite.globalNode);
    }

    if (!engine.warnings().empty() && ImGui::CollapsingHeader("Warnings", ImGuiTreeNodeFlags_DefaultOpen))
        for (const std::string& w : engine.warnings()) ImGui::TextWrapped("%s", w.c_str());

    ImGui::TextDisabled("drag: orbit; right drag: pan; wheel: zoom; F: frame all; H: hide panel");
    ImGui::End();
}

} // namespace glcollide::viewer
