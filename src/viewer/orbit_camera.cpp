#include "viewer/orbit_camera.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace glcollide::viewer {
namespace {
constexpr double kRadiansPerPixel = 0.3 * 3.14159265358979323846 / 180.0;
const double kMaxElevation = glm::radians(89.0);
} // namespace

OrbitCamera::OrbitCamera(const render::View& view)
    : m_target(view.target), m_up(glm::normalize(view.up)), m_fovDeg(view.fovDeg) {
    // Any two unit vectors perpendicular to up (and to each other) span the orbit's plane.
    const glm::dvec3 helper = std::abs(m_up.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
    m_e1 = glm::normalize(helper - glm::dot(helper, m_up) * m_up);
    m_e2 = glm::cross(m_e1, m_up);
    const glm::dvec3 toEye = view.eye - view.target;
    // sceneView never gives eye = target (finishView rejects it); 1 µm only keeps the division finite.
    m_distance = std::max(glm::length(toEye), 1e-6);
    const glm::dvec3 d = toEye / m_distance;
    m_elevation =
        std::clamp(std::asin(std::clamp(glm::dot(d, m_up), -1.0, 1.0)), -kMaxElevation, kMaxElevation);
    m_azimuth = std::atan2(glm::dot(d, m_e2), glm::dot(d, m_e1));
}

glm::dvec3 OrbitCamera::eye() const {
    const glm::dvec3 d = std::cos(m_elevation) * (std::cos(m_azimuth) * m_e1 + std::sin(m_azimuth) * m_e2) +
                         std::sin(m_elevation) * m_up;
    return m_target + m_distance * d;
}

void OrbitCamera::orbit(double dx, double dy) {
    m_azimuth -= dx * kRadiansPerPixel;
    m_elevation = std::clamp(m_elevation + dy * kRadiansPerPixel, -kMaxElevation, kMaxElevation);
}

void OrbitCamera::pan(double dx, double dy, int viewportHeight) {
    const glm::dvec3 forward = glm::normalize(m_target - eye());
    const glm::dvec3 right = glm::normalize(glm::cross(forward, m_up));
    const glm::dvec3 up = glm::cross(right, forward);
    // Metres per pixel in the plane through the target.
    const double scale =
        2.0 * m_distance * std::tan(glm::radians(m_fovDeg) / 2.0) / std::max(viewportHeight, 1);
    m_target += scale * (-dx * right + dy * up);
}

void OrbitCamera::zoom(double steps) {
    // 0.1 mm to 1000 km: beyond either the depth range (far / 1000 near) loses the scene.
    m_distance = std::clamp(m_distance * std::pow(0.9, steps), 1e-4, 1e6);
}

void OrbitCamera::frame(const glm::dvec3& lo, const glm::dvec3& hi, double aspect) {
    m_target = 0.5 * (lo + hi);
    const double radius =
        std::max(0.5 * glm::length(hi - lo), 1e-3); // a single node still gets 1 mm, as render's view
    // The sphere fits the narrower of the two fields of view, with a 10 % margin.
    const double halfY = glm::radians(m_fovDeg) / 2.0;
    const double halfX = std::atan(std::tan(halfY) * aspect);
    m_distance = 1.1 * radius / std::sin(std::min(halfX, halfY));
}

render::View OrbitCamera::view(double aspect, double sceneRadius) const {
    const double farPlane = m_distance + 2.0 * sceneRadius;
    return render::lookAtView(eye(), m_target, m_up, m_fovDeg, farPlane / 1000.0, farPlane, aspect);
}

} // namespace glcollide::viewer
