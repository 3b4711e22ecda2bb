#include "core/spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

namespace snell {

namespace {

// Jakob & Hanika 2019, "A Low-Dimensional Function Space for Efficient Spectral Upsampling":
// a spectrum is S(lambda) = sigmoid(c0 x^2 + c1 x + c2) with the algebraic sigmoid below.
// We use the normalised wavelength x in [0,1] over the sampled range for conditioning.
double sigmoid(double x) {
    if (std::isinf(x)) return x > 0 ? 1.0 : 0.0;
    return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x));
}
double norm_lambda(double lambda) { return (lambda - kLambdaMin) / (kLambdaMax - kLambdaMin); }
double sigmoid_poly(const double c[3], double lambda) {
    const double x = norm_lambda(lambda);
    return sigmoid((c[0] * x + c[1]) * x + c[2]);
}

// Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color
// Matching Functions": multi-lobe piecewise Gaussian fit of the CIE 1931 2-degree observer.
double g(double l, double mu, double s1, double s2) {
    const double t = (l - mu) / (l < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}

// Integration grid for fitting and normalisation (1 nm trapezoid).
constexpr int kGrid = int(kLambdaMax - kLambdaMin) + 1;
double grid_lambda(int i) { return kLambdaMin + double(i); }
double grid_weight(int i) { return (i == 0 || i == kGrid - 1) ? 0.5 : 1.0; }

Vec3 mat3(const double m[3][3], const Vec3& v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
// sRGB (Rec. 709 primaries, D65) <-> XYZ, IEC 61966-2-1.
constexpr double kXyzToSrgb[3][3] = {
    {3.2404542, -1.5371385, -0.4985314}, {-0.9692660, 1.8760108, 0.0415560}, {0.0556434, -0.2040259, 1.0572252}};
constexpr double kSrgbToXyz[3][3] = {
    {0.4124564, 0.3575761, 0.1804375}, {0.2126729, 0.7151522, 0.0721750}, {0.0193339, 0.1191920, 0.9503041}};

// Linear sRGB of sigmoid(c) weighted by spectrum w (w == nullptr: equal energy), normalised
// so that a constant 1 gives Y = 1 under that weight.
struct Weighting {
    std::array<double, kGrid> w;
    double y_norm;
};
// `stride` > 1 integrates on every stride-th nanometre (the texture table's coarser fits).
Vec3 fit_rgb(const double c[3], const Weighting& wt, int stride = 1) {
    Vec3 xyz;
    for (int i = 0; i < kGrid; i += stride) {
        const double l = grid_lambda(i);
        xyz += cie_xyz(l) * (sigmoid_poly(c, l) * wt.w[i] * grid_weight(i));
    }
    return mat3(kXyzToSrgb, xyz * double(stride) / wt.y_norm);
}

bool solve3(double a[3][3], double b[3], double x[3]) {
    // Cramer's rule is enough for a 3x3 with damping added on the diagonal.
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (!(std::abs(det) > 1e-300)) return false;
    for (int k = 0; k < 3; ++k) {
        double m[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = j == k ? b[i] : a[i][j];
        x[k] = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) /
               det;
    }
    return true;
}

// One Levenberg-Marquardt solve from the coefficients in c towards `goal`.
void lm_fit(const Vec3& goal, const Weighting& wt, int stride, double c[3]) {
    {
        double lambda_lm = 1e-3;
        for (int it = 0; it < 60; ++it) {
            const Vec3 r = fit_rgb(c, wt, stride) - goal;
            const double err = length_squared(r);
            if (err < 1e-14) break;
            double J[3][3];
            for (int k = 0; k < 3; ++k) {
                double cp[3] = {c[0], c[1], c[2]};
                const double h = 1e-6 * std::max(1.0, std::abs(c[k]));
                cp[k] += h;
                const Vec3 d = (fit_rgb(cp, wt, stride) - goal - r) / h;
                for (int i = 0; i < 3; ++i) J[i][k] = d[i];
            }
            // Normal equations (J^T J + mu diag) dx = -J^T r
            double A[3][3], b[3], dx[3];
            for (int i = 0; i < 3; ++i) {
                b[i] = 0;
                for (int k = 0; k < 3; ++k) b[i] -= J[k][i] * r[k];
                for (int j = 0; j < 3; ++j) {
                    A[i][j] = 0;
                    for (int k = 0; k < 3; ++k) A[i][j] += J[k][i] * J[k][j];
                }
            }
            bool improved = false;
            for (int tries = 0; tries < 20 && !improved; ++tries) {
                double Ad[3][3];
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) Ad[i][j] = A[i][j] + (i == j ? lambda_lm * (A[i][i] + 1e-12) : 0.0);
                if (!solve3(Ad, b, dx)) {
                    lambda_lm *= 10;
                    continue;
                }
                const double cn[3] = {c[0] + dx[0], c[1] + dx[1], c[2] + dx[2]};
                if (length_squared(fit_rgb(cn, wt, stride) - goal) < err) {
                    c[0] = cn[0], c[1] = cn[1], c[2] = cn[2];
                    lambda_lm = std::max(1e-9, lambda_lm * 0.3);
                    improved = true;
                } else {
                    lambda_lm *= 10;
                }
            }
            if (!improved) break;
        }
    }
}

// Levenberg-Marquardt fit of the three coefficients so that the sigmoid spectrum reproduces
// `target` (linear sRGB, components in (0,1)) under weighting wt. Continuation from grey
// towards the target keeps the solver in the basin of the smooth solution (as in the paper's
// table construction).
void fit_sigmoid(const RGB& target, const Weighting& wt, double c[3], int stride = 1) {
    c[0] = c[1] = c[2] = 0.0;  // sigmoid(0) = 0.5: grey
    const int kSteps = 8;
    for (int step = 1; step <= kSteps; ++step) {
        const double s = double(step) / kSteps;
        lm_fit(Vec3(0.5 + s * (target.r - 0.5), 0.5 + s * (target.g - 0.5), 0.5 + s * (target.b - 0.5)), wt, stride, c);
    }
}

const Weighting& equal_energy() {
    static const Weighting wt = [] {
        Weighting w;
        w.w.fill(1.0);
        w.y_norm = cie_y_integral();
        return w;
    }();
    return wt;
}

// The renderer's white illuminant: the smooth spectrum whose XYZ is sRGB white (D65
// chromaticity, Y = 1). Emission RGB is relative to it, and reflectances are fitted under it,
// so a white surface under a white light renders exactly white.
struct WhiteIlluminant {
    double c[3];
    double scale = 2.0;
    double eval(double l) const { return scale * sigmoid_poly(c, l); }
};
const WhiteIlluminant& white() {
    static const WhiteIlluminant w = [] {
        WhiteIlluminant wi;
        const Vec3 xyz = mat3(kSrgbToXyz, Vec3(1, 1, 1)) / wi.scale;
        const Vec3 rgb = mat3(kXyzToSrgb, xyz);  // == (0.5, 0.5, 0.5) up to rounding
        // Fit in XYZ-equivalent sRGB coordinates under equal energy.
        fit_sigmoid(RGB(rgb.x, rgb.y, rgb.z), equal_energy(), wi.c);
        return wi;
    }();
    return w;
}

const Weighting& white_weighting() {
    static const Weighting wt = [] {
        Weighting w;
        double y = 0;
        for (int i = 0; i < kGrid; ++i) {
            w.w[i] = white().eval(grid_lambda(i));
            y += cie_xyz(grid_lambda(i)).y * w.w[i] * grid_weight(i);
        }
        w.y_norm = y;
        return w;
    }();
    return wt;
}

RGB clamp_rgb(const RGB& c, double lo, double hi) {
    return {clamp(c.r, lo, hi), clamp(c.g, lo, hi), clamp(c.b, lo, hi)};
}

}  // namespace

static Vec3 cie_xyz_fit(double l) {
    return {1.056 * g(l, 599.8, 37.9, 31.0) + 0.362 * g(l, 442.0, 16.0, 26.7) - 0.065 * g(l, 501.1, 20.4, 26.2),
            0.821 * g(l, 568.8, 46.9, 40.5) + 0.286 * g(l, 530.9, 16.3, 31.1),
            1.217 * g(l, 437.0, 11.8, 36.0) + 0.681 * g(l, 459.0, 26.0, 13.8)};
}

Vec3 cie_xyz(double l) {
    // The fit tabulated at 1 nm and interpolated linearly: the film converts every wavelength
    // of every path, and the fit costs six exp() calls (relative error of the table < 1e-5).
    static const std::vector<Vec3> table = [] {
        std::vector<Vec3> t(static_cast<size_t>(kGrid));
        for (int i = 0; i < kGrid; ++i) t[size_t(i)] = cie_xyz_fit(grid_lambda(i));
        return t;
    }();
    if (!(l >= kLambdaMin) || !(l <= kLambdaMax)) return cie_xyz_fit(l);
    const double x = l - kLambdaMin;
    const int i = std::min(kGrid - 2, int(x));
    const double t = x - i;
    return table[size_t(i)] * (1 - t) + table[size_t(i) + 1] * t;
}

double cie_y_integral() {
    static const double v = [] {
        // Fine Simpson rule; the film estimator divides by exactly this value.
        const int n = 47000;
        const double h = (kLambdaMax - kLambdaMin) / n;
        double s = cie_xyz(kLambdaMin).y + cie_xyz(kLambdaMax).y;
        for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * cie_xyz(kLambdaMin + i * h).y;
        return s * h / 3.0;
    }();
    return v;
}

Vec3 xyz_to_linear_srgb(const Vec3& xyz) { return mat3(kXyzToSrgb, xyz); }
Vec3 linear_srgb_to_xyz(const Vec3& rgb) { return mat3(kSrgbToXyz, rgb); }

Vec3 spectrum_to_xyz(const Spectrum& s) {
    Vec3 xyz;
    for (int i = 0; i < kGrid; ++i) xyz += cie_xyz(grid_lambda(i)) * (s.eval(grid_lambda(i)) * grid_weight(i));
    return xyz / cie_y_integral();
}

// pbrt-v4's visible-wavelength density, proportional to 1/cosh^2(0.0072 (lambda - 538)) on
// [360, 830] nm, concentrates samples where the eye is sensitive. Its inverse CDF needs atanh,
// and four wavelengths are drawn for every camera sample: that was a tenth of `path`'s time on the
// droplet. So the inverse CDF is tabulated exactly at kVisibleBins + 1 knots and interpolated
// linearly between them: the wavelengths are then drawn exactly from the piecewise-constant
// density that takes the closed form's mass in each bin (within 0.3 % of the closed form), and
// that density, not the closed form, is the one every estimator divides by.
namespace {
constexpr int kVisibleBins = 1024;
struct VisibleTable {
    std::array<double, kVisibleBins + 1> lambda{};  ///< inverse CDF at u = k / kVisibleBins
    std::array<double, kVisibleBins> pdf{};         ///< density on bin k: 1 / (bins * width)
};
const VisibleTable& visible_table() {
    static const VisibleTable t = [] {
        VisibleTable v;
        const double a = std::tanh(0.0072 * (kLambdaMin - 538.0)), b = std::tanh(0.0072 * (kLambdaMax - 538.0));
        for (int k = 0; k <= kVisibleBins; ++k)
            v.lambda[size_t(k)] = 538.0 + std::atanh(a + (b - a) * k / kVisibleBins) / 0.0072;
        v.lambda.front() = kLambdaMin;
        v.lambda.back() = kLambdaMax;
        for (int k = 0; k < kVisibleBins; ++k)
            v.pdf[size_t(k)] = 1.0 / (kVisibleBins * (v.lambda[size_t(k) + 1] - v.lambda[size_t(k)]));
        return v;
    }();
    return t;
}
}  // namespace

double sample_visible_wavelength(double u, double* pdf) {
    const VisibleTable& t = visible_table();
    const double x = clamp(u, 0.0, 1.0) * kVisibleBins;
    const int k = std::min(kVisibleBins - 1, int(x));
    const double f = x - k;
    if (pdf) *pdf = t.pdf[size_t(k)];
    return t.lambda[size_t(k)] * (1 - f) + t.lambda[size_t(k) + 1] * f;
}
double visible_wavelength_pdf(double lambda) {
    if (!(lambda >= kLambdaMin) || !(lambda <= kLambdaMax)) return 0;
    const VisibleTable& t = visible_table();
    // The bin holding lambda (the knots increase with k).
    const auto it = std::upper_bound(t.lambda.begin() + 1, t.lambda.end() - 1, lambda);
    return t.pdf[size_t(it - t.lambda.begin() - 1)];
}

SampledWavelengths SampledWavelengths::sample_visible(const Vec2& u, int count) {
    SampledWavelengths wl;
    wl.m_count = std::clamp(count, 1, kSpectrumSamples);
    const int n = wl.m_count;
    const int hero = std::min(n - 1, int(u.y * n));
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (i >= n) {  // unused slots repeat the hero and carry no weight
            wl.m_lambda[size_t(i)] = wl.m_lambda[0];
            wl.m_pdf[size_t(i)] = 0;
            continue;
        }
        const double ui = (u.x + double((hero + i) % n)) / n;
        wl.m_lambda[size_t(i)] = sample_visible_wavelength(std::min(ui, 1.0 - 0x1p-53), &wl.m_pdf[size_t(i)]);
    }
    return wl;
}

SampledWavelengths SampledWavelengths::single(double lambda, double pdf) {
    SampledWavelengths wl;
    wl.m_count = 1;
    wl.m_lambda.fill(lambda);
    wl.m_pdf.fill(0);
    wl.m_pdf[0] = pdf;
    return wl;
}

Vec3 SampledWavelengths::to_xyz(const SampledSpectrum& L) const {
    Vec3 xyz;
    for (int i = 0; i < m_count; ++i)
        if (m_pdf[size_t(i)] > 0 && L[i] != 0) xyz += cie_xyz(m_lambda[size_t(i)]) * (L[i] / m_pdf[size_t(i)]);
    return xyz / (double(m_count) * cie_y_integral());
}

Spectrum Spectrum::constant(double v) {
    Spectrum s;
    s.m_kind = Kind::Constant;
    s.m_c[0] = v;
    return s;
}

Spectrum Spectrum::from_rgb_reflectance(const RGB& rgb_in) {
    const RGB rgb = clamp_rgb(rgb_in, 0.0, 1.0);
    if (rgb.r == rgb.g && rgb.g == rgb.b) return constant(rgb.r);
    // The sigmoid never reaches 0 or 1 exactly; stay just inside.
    const RGB t = clamp_rgb(rgb, 1e-4, 1 - 1e-4);
    static std::mutex mutex;
    static std::map<std::array<double, 3>, std::array<double, 3>> cache;
    const std::array<double, 3> key{t.r, t.g, t.b};
    Spectrum s;
    s.m_kind = Kind::Sigmoid;
    {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = cache.find(key);
        if (it != cache.end()) {
            std::copy(it->second.begin(), it->second.end(), s.m_c);
            return s;
        }
    }
    fit_sigmoid(t, white_weighting(), s.m_c);
    std::lock_guard<std::mutex> lock(mutex);
    cache[key] = {s.m_c[0], s.m_c[1], s.m_c[2]};
    return s;
}

Spectrum Spectrum::from_rgb_unbounded(const RGB& rgb_in) {
    const RGB rgb = clamp_rgb(rgb_in, 0.0, kInfinity);
    const double m = rgb.max();
    if (m <= 0) return constant(0);
    if (rgb.r == rgb.g && rgb.g == rgb.b) return constant(m);
    // pbrt-v4's RGBUnboundedSpectrum: scale 2 max, so the fitted part stays within (0, 0.5].
    const double scale = 2 * m;
    Spectrum s = from_rgb_reflectance(RGB(rgb.r / scale, rgb.g / scale, rgb.b / scale));
    return s.scaled(scale);
}

Spectrum Spectrum::from_rgb_illuminant(const RGB& rgb) {
    // Reflectance-like factor times the white illuminant.
    Spectrum s = from_rgb_unbounded(rgb);
    const WhiteIlluminant& w = white();
    Spectrum out;
    out.m_kind = Kind::Sigmoid;
    if (s.m_kind == Kind::Constant) {
        // Constant factor: the white illuminant itself, scaled.
        std::copy(w.c, w.c + 3, out.m_c);
        out.m_scale = w.scale * s.m_c[0];
        out.m_illum = false;
        return out;
    }
    std::copy(s.m_c, s.m_c + 3, out.m_c);
    out.m_scale = s.m_scale;
    out.m_illum = true;
    return out;
}

Spectrum Spectrum::from_ior_abbe(double n_d, double abbe) {
    // No dispersion is a constant spectrum, not a Cauchy one with B = 0: the BSDFs ask
    // is_constant() whether a refraction keeps every wavelength of the path (issue 26: a
    // B = 0 Cauchy made every dielectric without `abbe` keep the hero wavelength alone).
    if (!(abbe > 0) || std::isinf(abbe)) return constant(n_d);
    Spectrum s;
    s.m_kind = Kind::Cauchy;
    // Fraunhofer lines d, F, C (nm); V_d = (n_d - 1) / (n_F - n_C).
    const double ld = 587.56, lF = 486.13, lC = 656.27;
    const double B = (n_d - 1.0) / (abbe * (1.0 / (lF * lF) - 1.0 / (lC * lC)));
    s.m_c[0] = n_d - B / (ld * ld);
    s.m_c[1] = B;
    return s;
}

Spectrum Spectrum::tabulated(std::vector<double> lambda, std::vector<double> values) {
    if (lambda.empty() || lambda.size() != values.size())
        throw std::invalid_argument("tabulated spectrum: need equally many wavelengths and values");
    for (size_t i = 1; i < lambda.size(); ++i)
        if (!(lambda[i] > lambda[i - 1])) throw std::invalid_argument("tabulated spectrum: wavelengths must increase");
    Spectrum s;
    s.m_kind = Kind::Tabulated;
    s.m_lambda = std::make_shared<const std::vector<double>>(std::move(lambda));
    s.m_values = std::make_shared<const std::vector<double>>(std::move(values));
    return s;
}

double Spectrum::eval(double lambda) const {
    switch (m_kind) {
        case Kind::Constant:
            return m_c[0];
        case Kind::Sigmoid: {
            const double v = m_scale * sigmoid_poly(m_c, lambda);
            return m_illum ? v * white().eval(lambda) : v;
        }
        case Kind::Cauchy:
            return m_c[0] + m_c[1] / (lambda * lambda);
        case Kind::Tabulated: {
            const auto& L = *m_lambda;
            const auto& V = *m_values;
            if (lambda <= L.front()) return V.front() * m_scale;
            if (lambda >= L.back()) return V.back() * m_scale;
            const size_t i = size_t(std::upper_bound(L.begin(), L.end(), lambda) - L.begin()) - 1;
            const double t = (lambda - L[i]) / (L[i + 1] - L[i]);
            return m_scale * lerp(t, V[i], V[i + 1]);
        }
    }
    return 0;
}

double Spectrum::average() const {
    if (m_kind == Kind::Constant) return m_c[0];
    double s = 0, wsum = 0;
    for (int i = 0; i < kGrid; ++i) {
        s += eval(grid_lambda(i)) * grid_weight(i);
        wsum += grid_weight(i);
    }
    return s / wsum;
}

double Spectrum::max_value() const {
    if (m_kind == Kind::Constant) return m_c[0];
    double m = 0;
    for (int i = 0; i < kGrid; ++i) m = std::max(m, eval(grid_lambda(i)));
    // Piecewise linear data peaks at its own knots, which need not lie on the grid.
    if (m_kind == Kind::Tabulated)
        for (double v : *m_values) m = std::max(m, v * m_scale);
    return m;
}

Spectrum Spectrum::scaled(double f) const {
    Spectrum s = *this;
    if (m_kind == Kind::Constant) {
        s.m_c[0] *= f;
    } else if (m_kind == Kind::Cauchy) {
        s.m_c[0] *= f;
        s.m_c[1] *= f;
    } else {
        s.m_scale *= f;
    }
    return s;
}

double named_ior(const std::string& name) {
    // Mitsuba's table of named dielectrics (IOR at the sodium d line).
    static const std::map<std::string, double> table = {
        {"vacuum", 1.0},      {"helium", 1.00004},         {"hydrogen", 1.00013},
        {"air", 1.00028},     {"carbon dioxide", 1.00045}, {"water", 1.3330},
        {"acetone", 1.36},    {"ethanol", 1.361},          {"carbon tetrachloride", 1.461},
        {"glycerol", 1.4729}, {"benzene", 1.501},          {"silicone oil", 1.52045},
        {"bromine", 1.661},   {"water ice", 1.31},         {"fused quartz", 1.458},
        {"pyrex", 1.470},     {"acrylic glass", 1.49},     {"polypropylene", 1.49},
        {"bk7", 1.5046},      {"sodium chloride", 1.544},  {"amber", 1.55},
        {"pet", 1.5750},      {"diamond", 2.419},
    };
    auto it = table.find(name);
    if (it == table.end()) {
        std::string known;
        for (auto& [k, v] : table) known += (known.empty() ? "" : ", ") + k;
        throw std::invalid_argument("unknown named IOR '" + name + "' (known: " + known + ")");
    }
    return it->second;
}

double sigmoid_polynomial(const std::array<double, 3>& c, double lambda) { return sigmoid_poly(c.data(), lambda); }

void fit_reflectance_sigmoid(const RGB& rgb, std::array<double, 3>& c, bool warm_start, int stride) {
    const RGB t = clamp_rgb(rgb, 1e-4, 1 - 1e-4);
    if (warm_start)
        lm_fit(Vec3(t.r, t.g, t.b), white_weighting(), stride, c.data());
    else
        fit_sigmoid(t, white_weighting(), c.data(), stride);
}

}  // namespace snell
