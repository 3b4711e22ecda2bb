#pragma once
// Hero-wavelength spectral sampling (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling";
// pbrt-v4 and Mitsuba 3 do the same): every path carries kSpectrumSamples wavelengths,
// stratified over the visible range. Directions are sampled for the first (hero) wavelength;
// the others reuse them and weight the estimate by their own BSDF and emission values, which
// removes nearly all colour noise wherever nothing disperses. Where the sampled direction
// exists for the hero alone (refraction through a dispersive interface) the others are
// dropped and the hero counts for all of them (terminate_secondary()).
#include <algorithm>
#include <array>
#include <cmath>

#include "core/vector.h"

namespace snell {

constexpr int kSpectrumSamples = 4;

/// Values of a spectral quantity at the path's wavelengths (radiance, throughput, BSDF value,
/// transmittance). Element-wise arithmetic. Value type of four doubles.
class SampledSpectrum {
public:
    SampledSpectrum() { m_v.fill(0.0); }
    explicit SampledSpectrum(double c) { m_v.fill(c); }

    double operator[](int i) const { return m_v[size_t(i)]; }
    double& operator[](int i) { return m_v[size_t(i)]; }

#define SNELL_SAMPLED_OP(op)                                                               \
    SampledSpectrum& operator op##=(const SampledSpectrum& o) {                            \
        for (int i = 0; i < kSpectrumSamples; ++i) m_v[size_t(i)] op## = o.m_v[size_t(i)]; \
        return *this;                                                                      \
    }                                                                                      \
    SampledSpectrum operator op(const SampledSpectrum& o) const {                          \
        SampledSpectrum r = *this;                                                         \
        return r op## = o;                                                                 \
    }
    SNELL_SAMPLED_OP(+)
    SNELL_SAMPLED_OP(-)
    SNELL_SAMPLED_OP(*)
#undef SNELL_SAMPLED_OP
    SampledSpectrum& operator*=(double s) {
        for (double& v : m_v) v *= s;
        return *this;
    }
    SampledSpectrum& operator/=(double s) { return *this *= 1.0 / s; }
    SampledSpectrum operator*(double s) const {
        SampledSpectrum r = *this;
        return r *= s;
    }
    SampledSpectrum operator/(double s) const { return *this * (1.0 / s); }
    friend SampledSpectrum operator*(double s, const SampledSpectrum& v) { return v * s; }
    bool is_zero() const {
        for (double v : m_v)
            if (v != 0) return false;
        return true;
    }
    bool is_nonzero() const { return !is_zero(); }  ///< some wavelength carries a value
    double max_component() const { return *std::max_element(m_v.begin(), m_v.end()); }
    double average() const { return (m_v[0] + m_v[1] + m_v[2] + m_v[3]) / kSpectrumSamples; }

private:
    std::array<double, kSpectrumSamples> m_v;
};

inline SampledSpectrum exp(const SampledSpectrum& s) {
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i) r[i] = std::exp(s[i]);
    return r;
}

/// The wavelengths (nm) a path carries and their sampling densities (1/nm). count() of them
/// are live: 4 by default, 1 for the paper's single-wavelength set-up (spectral_samples=1),
/// in which case the unused slots repeat the hero so every evaluation stays well defined.
class SampledWavelengths {
public:
    /// Stratified visible wavelengths from a uniform pair u: the count of them lie at
    /// (u.x + j) / count, j = 0 .. count-1, through the visible-range warp, and the hero (slot
    /// 0) is the j = floor(u.y count) one, the others following in order (mod count).
    /// pbrt-v4 takes (u + j/count) mod 1 instead; here, when a stratified sampler spreads u.x
    /// over a pixel's N samples, the N count wavelengths fall into N count distinct strata (with
    /// pbrt-v4's rule they share N strata), which divides the colour noise per pixel by about 3
    /// at 64 spp. Every slot, the hero included, is uniform over the range, so a path that keeps
    /// the hero alone (hero_only) stays unbiased.
    static SampledWavelengths sample_visible(const Vec2& u, int count = kSpectrumSamples);
    /// A single wavelength with density `pdf` (tests, and integrators that fix lambda).
    static SampledWavelengths single(double lambda, double pdf = 1.0);

    double operator[](int i) const { return m_lambda[size_t(i)]; }
    double pdf(int i) const { return m_pdf[size_t(i)]; }
    double hero() const { return m_lambda[0]; }
    int count() const { return m_count; }

    /// CIE XYZ estimate of the radiance L carried at these wavelengths:
    /// (1/count) sum_i L_i cmf(lambda_i) / (pdf_i * integral of y-bar).
    Vec3 to_xyz(const SampledSpectrum& L) const;

    /// The hero wavelength's value times count(), the others zero: multiply the part of an
    /// estimate that exists for the hero only (its direction was refracted dispersively) by
    /// this once, so the hero carries the secondaries' share and the estimate stays unbiased.
    SampledSpectrum hero_only(const SampledSpectrum& v) const {
        SampledSpectrum r;
        r[0] = v[0] * double(m_count);
        return r;
    }

private:
    std::array<double, kSpectrumSamples> m_lambda{}, m_pdf{};
    int m_count = kSpectrumSamples;
};

}  // namespace snell
