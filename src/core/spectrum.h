#pragma once
// Spectral quantities: functions of wavelength (Spectrum), evaluated at the wavelengths a path
// carries (SampledWavelengths, core/sampled_spectrum.h) to SampledSpectrum values.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/sampled_spectrum.h"
#include "core/vector.h"

namespace snell {

constexpr double kLambdaMin = 360.0;  ///< nm, range of wavelength sampling and CMFs
constexpr double kLambdaMax = 830.0;  ///< nm

/// Linear sRGB (Rec. 709 primaries, D65 white) triple.
struct RGB {
    double r = 0, g = 0, b = 0;
    constexpr RGB() = default;
    constexpr RGB(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit RGB(double v) : r(v), g(v), b(v) {}
    double max() const { return std::max(r, std::max(g, b)); }
    double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

/// A function of wavelength (nm). Value type; cheap to copy.
class Spectrum {
public:
    enum class Kind { Constant, Sigmoid, Cauchy, Tabulated };

    Spectrum() = default;  ///< constant zero
    static Spectrum constant(double v);
    /// Reflectance-like RGB in [0,1], upsampled with Jakob & Hanika 2019 (sigmoid of a
    /// quadratic polynomial) so that it reproduces `rgb` under the white illuminant below.
    static Spectrum from_rgb_reflectance(const RGB& rgb);
    /// Unbounded non-negative RGB (absorption coefficients, IOR-like data): scale * sigmoid.
    static Spectrum from_rgb_unbounded(const RGB& rgb);
    /// Emitted radiance: rgb(1,1,1) is the renderer's white (maps to sRGB (1,1,1)).
    static Spectrum from_rgb_illuminant(const RGB& rgb);
    /// Dispersive IOR from n_d (at 587.56 nm) and the Abbe number V_d, by Cauchy's
    /// equation n = A + B / lambda^2. V_d <= 0 (or infinite) means no dispersion.
    static Spectrum from_ior_abbe(double n_d, double abbe);
    /// Piecewise linear data (wavelengths ascending, nm); clamped to the end values outside.
    static Spectrum tabulated(std::vector<double> lambda, std::vector<double> values);

    double eval(double lambda) const;
    double operator()(double lambda) const { return eval(lambda); }
    /// Values at every wavelength a path carries.
    SampledSpectrum eval(const SampledWavelengths& wl) const {
        SampledSpectrum r;
        if (m_kind == Kind::Constant) return SampledSpectrum(m_c[0]);
        for (int i = 0; i < kSpectrumSamples; ++i) r[i] = eval(wl[i]);
        return r;
    }
    /// Mean over [kLambdaMin, kLambdaMax].
    double average() const;
    /// Upper bound over the visible range.
    double max_value() const;
    bool is_constant() const { return m_kind == Kind::Constant; }
    double constant_value() const { return m_c[0]; }
    Kind kind() const { return m_kind; }
    /// Multiplies values by s (exact for every kind).
    Spectrum scaled(double s) const;

private:
    Kind m_kind = Kind::Constant;
    double m_c[3] = {0, 0, 0};  // constant: c0; sigmoid: polynomial coefficients; cauchy: A, B
    double m_scale = 1.0;
    bool m_illum = false;  // sigmoid part is multiplied by the white illuminant
    std::shared_ptr<const std::vector<double>> m_lambda, m_values;  // tabulated
};

/// CIE 1931 2-degree colour matching functions (x̄, ȳ, z̄) at `lambda` nm.
Vec3 cie_xyz(double lambda);
/// Integral of ȳ over [kLambdaMin, kLambdaMax] (normalises spectral radiance to Y).
double cie_y_integral();
/// XYZ of a spectrum, normalised so that the constant 1 spectrum has Y = 1.
Vec3 spectrum_to_xyz(const Spectrum& s);

Vec3 xyz_to_linear_srgb(const Vec3& xyz);
Vec3 linear_srgb_to_xyz(const Vec3& rgb);

/// Samples a wavelength over [kLambdaMin, kLambdaMax] proportionally to a smooth fit of the
/// visual response (pbrt-v4's 1/cosh^2 density, tabulated: see spectrum.cpp), for low colour
/// noise. The density at the returned wavelength goes to `pdf` when given; it equals
/// visible_wavelength_pdf() there.
double sample_visible_wavelength(double u, double* pdf = nullptr);
double visible_wavelength_pdf(double lambda);

/// Named IOR of a dielectric ("water", "bk7", "air", ...) at the d line; throws on unknown.
double named_ior(const std::string& name);

/// Jakob & Hanika's sigmoid(c0 x^2 + c1 x + c2), x the wavelength normalised to [0, 1] over
/// [kLambdaMin, kLambdaMax]: the reflectance spectra of from_rgb_reflectance.
double sigmoid_polynomial(const std::array<double, 3>& c, double lambda);
/// Fits c so that sigmoid_polynomial(c) reproduces the reflectance `rgb` (clamped into (0, 1))
/// under the renderer's white: from grey by continuation, or (`warm_start`) from c as given, a
/// neighbour's coefficients. `stride` > 1 integrates on every stride-th nm (faster, for tables).
void fit_reflectance_sigmoid(const RGB& rgb, std::array<double, 3>& c, bool warm_start, int stride = 1);

}  // namespace snell
