#pragma once
/// \file The integration experiment's `oscillator` reference (docs/benchmarks.md, "The oscillator
/// reference"): the closed form of a damped spring-mass oscillator, and the estimators that read a
/// period and an amplitude decay off a trajectory sampled once per frame. No GL: unit-tested on
/// synthetic samples (tests/unit/benchkit_test.cpp).

#include <vector>

namespace glcollide::benchkit {

/// m u'' + c u' + k u = 0 with u(0) = u0, u'(0) = v0, underdamped (ζ < 1). u is the displacement
/// from the rest length along the spring.
struct DampedOscillator {
    double mass = 1.0;      ///< kg
    double stiffness = 1.0; ///< N/m
    double damping = 0.0;   ///< N·s/m (all linear damping on the node, spring and air)
    double u0 = 0.0;        ///< m
    double v0 = 0.0;        ///< m/s

    [[nodiscard]] double omega() const;  ///< undamped angular frequency sqrt(k/m), rad/s
    [[nodiscard]] double zeta() const;   ///< damping ratio c / (2 sqrt(k m))
    [[nodiscard]] double decay() const;  ///< ζω = c / (2m), 1/s
    [[nodiscard]] double omegaD() const; ///< damped angular frequency ω sqrt(1 - ζ²)
    [[nodiscard]] double period() const; ///< 2π / ω_d, s
    /// Ratio of consecutive peaks, e^{-ζω T_d}.
    [[nodiscard]] double amplitudeRatioPerPeriod() const;
    /// The envelope's starting value: |u(t)| <= amplitude() e^{-ζωt}.
    [[nodiscard]] double amplitude() const;
    /// u(t) = e^{-ζωt} (u0 cos ω_d t + (v0 + ζω u0)/ω_d sin ω_d t).
    [[nodiscard]] double displacement(double t) const;
    [[nodiscard]] double velocity(double t) const;
    /// ½ m u'² + ½ k u².
    [[nodiscard]] double energy(double t) const;
};

/// Times of the upward zero crossings (u_i <= 0 < u_{i+1}) of samples u_i taken at t = i·dt,
/// each by linear interpolation between the two samples.
std::vector<double> upwardZeroCrossings(const std::vector<double>& u, double dt);

/// Mean period (last crossing − first) / (crossings − 1); NaN with fewer than 2 crossings.
double meanPeriod(const std::vector<double>& crossings);

/// Bound on the linear interpolation's error in one crossing time of f(t) = B e^{−a t}
/// sin(ω_d (t − t*)) sampled every dt: ½ max|f''| / min|f'| · dt²/4 over the bracketing interval,
/// i.e. dt²/8 · e^{2a dt} (|a² − ω_d²| sin ω_d dt + 2aω_d) / (ω_d cos ω_d dt − a sin ω_d dt).
/// For a = 0 it is ω_d² dt³ / (8 cos ω_d dt). Infinite when ω_d dt is too coarse for the bound.
double crossingTimeBound(double omegaD, double decay, double dt);

/// One peak per period: the largest sample between each pair of consecutive upward crossings,
/// refined by the parabola through it and its two neighbours (crossings as upwardZeroCrossings
/// returns them).
std::vector<double> periodPeaks(const std::vector<double>& u, double dt,
                                const std::vector<double>& crossings);

/// Relative error bound of one periodPeaks peak of e^{−a t} cos(ω t) sampled every dt, to leading
/// order: 3φ⁴/128 + aω²dt³/8 with φ = ω dt. Expanding the curve about its peak as
/// 1 − κs²/2 + g3 s³ + g4 s⁴, the parabola through samples at (x − 1, x, x + 1)·dt (|x| <= 1/2)
/// misses the peak by dt³ g3 x(x² − 1) + dt⁴ 3 g4 (x⁴ − x²) + O(dt⁴ g3²); for the cosine g4 = ω⁴/24
/// and |x⁴ − x²| <= 3/16, with the decay g3 = aω²/3 + O(a²) and |x(x² − 1)| <= 3/8.
double peakBound(double omega, double decay, double dt);

/// Geometric mean of the ratios of consecutive peaks, (last / first)^(1 / (peaks − 1)); NaN with
/// fewer than 2 peaks or a non-positive one.
double meanAmplitudeRatio(const std::vector<double>& peaks);

/// Symplectic Euler (v += h a(x, v); x += h v) on m u'' + c u' + k u = 0 is the linear map of
/// docs/integration.md with determinant 1 − hγ (γ = c/m) and trace 2 − hγ − h²ω²; its eigenvalues
/// are sqrt(1 − hγ) e^{±iθ} with cos θ = trace / (2 sqrt(det)) (undamped: 2 − 2cos θ = h²ω²).
/// The discrete trajectory is a sampled damped sinusoid of period 2πh/θ and per-step amplitude
/// factor sqrt(1 − hγ). NaN when the map is not an oscillation (unstable or overdamped step).
double symplecticEulerPeriod(const DampedOscillator& o, double h);
double symplecticEulerAmplitudeRatioPerPeriod(const DampedOscillator& o, double h);

/// Implicit (backward) Euler (v' = v + h a(x', v'); x' = x + h v'), exact for this linear system in
/// one Newton step: with D = 1 + hγ + h²ω² the map is [[1 + hγ, h], [−hω², 1]] / D, determinant
/// 1/D and trace (2 + hγ)/D; eigenvalues D^{−1/2} e^{±iθ} with cos θ = (2 + hγ) / (2 sqrt(D))
/// (undamped: θ = atan(hω)). Period 2πh/θ (long by (hω)²/3 undamped), amplitude ratio D^{−π/θ}
/// per period (undamped ≈ e^{−πhω}: numerical damping). For checks once that integrator exists.
double implicitEulerPeriod(const DampedOscillator& o, double h);
double implicitEulerAmplitudeRatioPerPeriod(const DampedOscillator& o, double h);

} // namespace glcollide::benchkit
