#include "benchkit/oscillator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace glcollide::benchkit {

double DampedOscillator::omega() const {
    return std::sqrt(stiffness / mass);
}

double DampedOscillator::zeta() const {
    return damping / (2.0 * std::sqrt(stiffness * mass));
}

double DampedOscillator::decay() const {
    return damping / (2.0 * mass);
}

double DampedOscillator::omegaD() const {
    const double z = zeta();
    return omega() * std::sqrt(1.0 - z * z);
}

double DampedOscillator::period() const {
    return 2.0 * std::numbers::pi / omegaD();
}

double DampedOscillator::amplitudeRatioPerPeriod() const {
    return std::exp(-decay() * period());
}

double DampedOscillator::amplitude() const {
    const double s = (v0 + decay() * u0) / omegaD();
    return std::sqrt(u0 * u0 + s * s);
}

double DampedOscillator::displacement(double t) const {
    const double a = decay(), wd = omegaD();
    return std::exp(-a * t) * (u0 * std::cos(wd * t) + (v0 + a * u0) / wd * std::sin(wd * t));
}

double DampedOscillator::velocity(double t) const {
    const double a = decay(), wd = omegaD(), w = omega();
    return std::exp(-a * t) * (v0 * std::cos(wd * t) - (a * v0 + w * w * u0) / wd * std::sin(wd * t));
}

double DampedOscillator::energy(double t) const {
    const double u = displacement(t), v = velocity(t);
    return 0.5 * mass * v * v + 0.5 * stiffness * u * u;
}

std::vector<double> upwardZeroCrossings(const std::vector<double>& u, double dt) {
    std::vector<double> t;
    for (std::size_t i = 0; i + 1 < u.size(); ++i)
        if (u[i] <= 0.0 && u[i + 1] > 0.0) // false for NaN: a diverged run has no crossings there
            t.push_back(dt * (double(i) + u[i] / (u[i] - u[i + 1])));
    return t;
}

double meanPeriod(const std::vector<double>& crossings) {
    if (crossings.size() < 2) return std::numeric_limits<double>::quiet_NaN();
    return (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

double crossingTimeBound(double omegaD, double decay, double dt) {
    const double s = std::sin(omegaD * dt), c = std::cos(omegaD * dt);
    const double slope = omegaD * c - decay * s; // min |f'| / (|B| e^{-a dt}) within dt of the zero
    if (!(slope > 0.0) || omegaD * dt >= std::numbers::pi / 2) return std::numeric_limits<double>::infinity();
    const double curvature = std::abs(decay * decay - omegaD * omegaD) * s + 2.0 * decay * omegaD;
    return dt * dt / 8.0 * std::exp(2.0 * decay * dt) * curvature / slope;
}

std::vector<double> periodPeaks(const std::vector<double>& u, double dt,
                                const std::vector<double>& crossings) {
    std::vector<double> peaks;
    for (std::size_t k = 0; k + 1 < crossings.size(); ++k) {
        // Samples strictly after one crossing and up to the next.
        const auto first = static_cast<std::size_t>(std::floor(crossings[k] / dt)) + 1;
        const auto last = std::min(u.size() - 1, static_cast<std::size_t>(std::floor(crossings[k + 1] / dt)));
        if (first > last) continue;
        std::size_t m = first;
        for (std::size_t i = first; i <= last; ++i)
            if (u[i] > u[m]) m = i;
        double peak = u[m];
        if (m > 0 && m + 1 < u.size()) {
            const double a = u[m - 1], b = u[m], c = u[m + 1];
            const double denominator = a - 2.0 * b + c;
            if (denominator < 0.0) {
                const double p = 0.5 * (a - c) / denominator; // vertex offset in samples, |p| <= 1/2
                peak = b - 0.25 * (a - c) * p;
            }
        }
        peaks.push_back(peak);
    }
    return peaks;
}

double peakBound(double omega, double decay, double dt) {
    const double phi = omega * dt;
    return 3.0 * phi * phi * phi * phi / 128.0 + decay * omega * omega * dt * dt * dt / 8.0;
}

double meanAmplitudeRatio(const std::vector<double>& peaks) {
    if (peaks.size() < 2 || !(peaks.front() > 0.0) || !(peaks.back() > 0.0))
        return std::numeric_limits<double>::quiet_NaN();
    return std::pow(peaks.back() / peaks.front(), 1.0 / double(peaks.size() - 1));
}

namespace {

/// θ of the symplectic Euler map's eigenvalues sqrt(det) e^{±iθ}; NaN unless complex and inside.
double symplecticEulerTheta(const DampedOscillator& o, double h) {
    const double w = o.omega(), gamma = o.damping / o.mass;
    const double det = 1.0 - h * gamma, trace = 2.0 - h * gamma - h * h * w * w;
    if (!(det > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    const double c = trace / (2.0 * std::sqrt(det));
    if (!(std::abs(c) < 1.0)) return std::numeric_limits<double>::quiet_NaN();
    // Undamped, cos θ = 1 − h²ω²/2 is θ = 2 asin(hω/2): the same number without the cancellation.
    return gamma == 0.0 ? 2.0 * std::asin(0.5 * h * w) : std::acos(c);
}

} // namespace

double symplecticEulerPeriod(const DampedOscillator& o, double h) {
    return 2.0 * std::numbers::pi * h / symplecticEulerTheta(o, h);
}

double symplecticEulerAmplitudeRatioPerPeriod(const DampedOscillator& o, double h) {
    const double theta = symplecticEulerTheta(o, h);
    return std::pow(1.0 - h * o.damping / o.mass, std::numbers::pi / theta);
}

namespace {

double implicitEulerTheta(const DampedOscillator& o, double h) {
    const double w = o.omega(), gamma = o.damping / o.mass;
    const double d = 1.0 + h * gamma + h * h * w * w;
    const double c = (2.0 + h * gamma) / (2.0 * std::sqrt(d));
    if (!(std::abs(c) < 1.0)) return std::numeric_limits<double>::quiet_NaN(); // overdamped step
    return gamma == 0.0 ? std::atan(h * w) : std::acos(c);
}

} // namespace

double implicitEulerPeriod(const DampedOscillator& o, double h) {
    return 2.0 * std::numbers::pi * h / implicitEulerTheta(o, h);
}

double implicitEulerAmplitudeRatioPerPeriod(const DampedOscillator& o, double h) {
    const double w = o.omega(), gamma = o.damping / o.mass;
    return std::pow(1.0 + h * gamma + h * h * w * w, -std::numbers::pi / implicitEulerTheta(o, h));
}

} // namespace glcollide::benchkit
