#include "texture/bitmap.h"

#include <algorithm>
#include <cmath>

#include "core/rgb_to_spectrum_table.h"

namespace snell {

BitmapTexture::BitmapTexture(TextureImage image, Filter filter, Wrap wrap, bool raw, Transform to_uv)
    : m_width(image.width),
      m_height(image.height),
      m_channels(image.channels),
      m_texels(std::move(image.texels)),
      m_filter(filter),
      m_wrap(wrap),
      m_to_uv(to_uv) {
    if (image.srgb_encoded && !raw)
        for (float& v : m_texels) v = float(srgb_to_linear(v));
    const size_t n = size_t(m_width) * size_t(m_height);
    double sum = 0;
    m_min = INFINITY;
    m_max = -INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const float* t = &m_texels[i * size_t(m_channels)];
        const double v = m_channels == 1 ? t[0] : RGB(t[0], t[1], t[2]).luminance();
        sum += v;
        m_min = std::min(m_min, v);
        m_max = std::max(m_max, v);
    }
    m_mean = n ? sum / double(n) : 0.0;
}

int BitmapTexture::wrap(int i, int n) const { return wrap_index(i, n, m_wrap); }

BitmapTexture::Footprint BitmapTexture::footprint(const Vec2& uv_in) const {
    const Vec2 uv = transform_uv(m_to_uv, uv_in);
    Footprint f{};
    // Large |uv| (a to_uv that tiles thousands of times) stays exact in double before the cast.
    const double px = clamp(uv.x * m_width, -1e9, 1e9), py = clamp(uv.y * m_height, -1e9, 1e9);
    if (m_filter == Filter::Nearest || !std::isfinite(px) || !std::isfinite(py)) {
        f.count = 1;
        f.x[0] = wrap(std::isfinite(px) ? int(std::floor(px)) : 0, m_width);
        f.y[0] = wrap(std::isfinite(py) ? int(std::floor(py)) : 0, m_height);
        f.wx[0] = f.wy[0] = 1;
        return f;
    }
    // Bilinear between the texel centres around (px - 1/2, py - 1/2).
    const double x = px - 0.5, y = py - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    f.count = 2;
    f.x[0] = wrap(int(x0), m_width);
    f.x[1] = wrap(int(x0) + 1, m_width);
    f.y[0] = wrap(int(y0), m_height);
    f.y[1] = wrap(int(y0) + 1, m_height);
    f.wx[1] = x - x0;
    f.wx[0] = 1 - f.wx[1];
    f.wy[1] = y - y0;
    f.wy[0] = 1 - f.wy[1];
    return f;
}

RGB BitmapTexture::eval_rgb(const SurfaceInteraction& si) const {
    const Footprint f = footprint(si.uv);
    double c[3] = {0, 0, 0};
    for (int j = 0; j < f.count; ++j)
        for (int i = 0; i < f.count; ++i) {
            const float* t = texel(f.x[i], f.y[j]);
            const double w = f.wx[i] * f.wy[j];
            for (int k = 0; k < 3; ++k) c[k] += w * t[m_channels == 1 ? 0 : k];
        }
    return RGB(c[0], c[1], c[2]);
}

double BitmapTexture::eval_float(const SurfaceInteraction& si) const {
    const Footprint f = footprint(si.uv);
    double v = 0;
    for (int j = 0; j < f.count; ++j)
        for (int i = 0; i < f.count; ++i) v += f.wx[i] * f.wy[j] * texel_float(f.x[i], f.y[j]);
    return v;
}

Vec2 BitmapTexture::eval_float_grad(const SurfaceInteraction& si) const {
    const Footprint f = footprint(si.uv);
    if (f.count < 2) return Vec2(0, 0);
    const double f00 = texel_float(f.x[0], f.y[0]), f10 = texel_float(f.x[1], f.y[0]);
    const double f01 = texel_float(f.x[0], f.y[1]), f11 = texel_float(f.x[1], f.y[1]);
    // Per texel along x and y, then through the texel scale and to_uv's linear part.
    const double dx = f.wy[0] * (f10 - f00) + f.wy[1] * (f11 - f01);
    const double dy = f.wx[0] * (f01 - f00) + f.wx[1] * (f11 - f10);
    const Vec2 o = transform_uv(m_to_uv, Vec2(0, 0));
    const Vec2 cu = transform_uv(m_to_uv, Vec2(1, 0)) - o, cv = transform_uv(m_to_uv, Vec2(0, 1)) - o;
    return Vec2(m_width * dx * cu.x + m_height * dy * cu.y, m_width * dx * cv.x + m_height * dy * cv.y);
}

const std::vector<float>& BitmapTexture::coefficients() const {
    std::call_once(m_coeff_once, [this] {
        const RGBToSpectrumTable& table = RGBToSpectrumTable::reflectance();
        const size_t n = size_t(m_width) * size_t(m_height);
        m_coeffs.resize(3 * n);
        for (size_t i = 0; i < n; ++i) {
            const float* t = &m_texels[3 * i];
            const auto c = table(RGB(t[0], t[1], t[2]));
            for (size_t k = 0; k < 3; ++k) m_coeffs[3 * i + k] = float(c[k]);
        }
    });
    return m_coeffs;
}

SampledSpectrum BitmapTexture::eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const {
    if (m_channels == 1) return SampledSpectrum(eval_float(si));
    const std::vector<float>& coeffs = coefficients();
    const Footprint f = footprint(si.uv);
    SampledSpectrum out(0.0);
    for (int j = 0; j < f.count; ++j)
        for (int i = 0; i < f.count; ++i) {
            const double w = f.wx[i] * f.wy[j];
            if (w == 0) continue;
            const float* c = &coeffs[3 * (size_t(f.y[j]) * m_width + f.x[i])];
            const std::array<double, 3> cd{c[0], c[1], c[2]};
            for (int k = 0; k < kSpectrumSamples; ++k) out[k] += w * sigmoid_polynomial(cd, wl[k]);
        }
    return out;
}

}  // namespace snell
