#pragma once
// The viewer's camera: it orbits a target point about the scene's up axis, pans in the view plane
// and zooms by distance. Starts from the scene's view (render::sceneView: its `camera` or the
// renderer's default). GL-free.

#include "render/scene_renderer.hpp"

#include <glm/vec3.hpp>

namespace glcollide::viewer {

class OrbitCamera {
  public:
    /// The camera that sees what `view` sees (eye, target, up, field of view).
    explicit OrbitCamera(const render::View& view);

    [[nodiscard]] glm::dvec3 eye() const;
    [[nodiscard]] const glm::dvec3& target() const { return m_target; }
    /// Turns about the target: `dx`, `dy` in pixels (0.3 degrees each); the elevation stays within
    /// ±89 degrees, so the view never flips over the up axis.
    void orbit(double dx, double dy);
    /// Moves eye and target in the view plane so the point under the cursor follows it: `dx`, `dy`
    /// in pixels of a viewport `viewportHeight` pixels high.
    void pan(double dx, double dy, int viewportHeight);
    /// Wheel steps: each brings the eye 10 % closer (negative: farther).
    void zoom(double steps);
    /// Looks at the box [lo, hi] from the current direction, at the distance where its bounding
    /// sphere fills the view with a margin (`aspect` = width / height).
    void frame(const glm::dvec3& lo, const glm::dvec3& hi, double aspect);
    /// The view to draw with; the depth range covers `sceneRadius` around the target (the grid's
    /// square included).
    [[nodiscard]] render::View view(double aspect, double sceneRadius) const;

  private:
    glm::dvec3 m_target{0.0};
    glm::dvec3 m_up{0.0, 1.0, 0.0};
    glm::dvec3 m_e1{1.0, 0.0, 0.0}, m_e2{0.0, 0.0, 1.0}; ///< the plane perpendicular to m_up
    double m_distance = 1.0;
    double m_azimuth = 0.0;   ///< radians in the (e1, e2) plane
    double m_elevation = 0.0; ///< radians above that plane
    double m_fovDeg = 45.0;
};

} // namespace glcollide::viewer
