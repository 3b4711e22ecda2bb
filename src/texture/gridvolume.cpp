#include "texture/gridvolume.h"

#include <algorithm>
#include <cmath>

#include "core/rgb_to_spectrum_table.h"

namespace snell {

GridVolumeTexture::GridVolumeTexture(VolumeGrid grid, Transform to_world, bool nearest, WrapMode wrap, bool raw)
    : m_grid(std::move(grid)), m_to_local(to_world.inverse()), m_nearest(nearest), m_wrap(wrap), m_raw(raw) {
    const size_t n = size_t(m_grid.xres) * m_grid.yres * m_grid.zres;
    const int c = m_grid.channels;
    auto value = [&](size_t i) {
        const float* v = &m_grid.data[i * size_t(c)];
        return c == 1 ? double(v[0]) : RGB(v[0], v[1], v[2]).luminance();
    };
    m_min = m_max = value(0);
    for (size_t i = 0; i < n; ++i) {
        const double v = value(i);
        m_mean += v / double(n);
        m_min = std::min(m_min, v);
        m_max = std::max(m_max, v);
    }
    if (c == 3 && !m_raw) {
        // Mitsuba's upsampling of volume colours: the colour over twice its largest component
        // is a reflectance (any RGB fits), scaled back by that factor.
        const RGBToSpectrumTable& table = RGBToSpectrumTable::reflectance();
        m_coeffs.resize(4 * n);
        for (size_t i = 0; i < n; ++i) {
            const float* v = &m_grid.data[3 * i];
            const double scale = 2 * std::max({double(v[0]), double(v[1]), double(v[2]), 0.0});
            const double s = std::max(scale, 1e-8);
            const auto co = table(RGB(v[0] / s, v[1] / s, v[2] / s));
            for (int k = 0; k < 3; ++k) m_coeffs[4 * i + size_t(k)] = float(co[size_t(k)]);
            m_coeffs[4 * i + 3] = float(scale);
        }
    }
}

GridVolumeTexture::Footprint GridVolumeTexture::footprint(const Vec3& p_world) const {
    const Vec3 p = m_to_local.point(p_world);
    const int res[3] = {m_grid.xres, m_grid.yres, m_grid.zres};
    const double q[3] = {p.x, p.y, p.z};
    Footprint f;
    // Voxel centres at (i + 1/2) / res, as texel centres are.
    int i0[3];
    double t[3];
    for (int a = 0; a < 3; ++a) {
        const double x = q[a] * res[a] - (m_nearest ? 0.0 : 0.5);
        const double fl = std::floor(std::clamp(x, -1e9, 1e9));
        i0[a] = int(fl);
        t[a] = x - fl;
    }
    auto index = [&](int x, int y, int z) {
        return (size_t(wrap_index(z, res[2], m_wrap)) * size_t(res[1]) + size_t(wrap_index(y, res[1], m_wrap))) *
                   size_t(res[0]) +
               size_t(wrap_index(x, res[0], m_wrap));
    };
    if (m_nearest) {
        f.count = 1;
        f.voxel[0] = index(i0[0], i0[1], i0[2]);
        f.w[0] = 1;
        return f;
    }
    f.count = 8;
    for (int k = 0; k < 8; ++k) {
        const int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
        f.voxel[k] = index(i0[0] + dx, i0[1] + dy, i0[2] + dz);
        f.w[k] = (dx ? t[0] : 1 - t[0]) * (dy ? t[1] : 1 - t[1]) * (dz ? t[2] : 1 - t[2]);
    }
    return f;
}

SampledSpectrum GridVolumeTexture::eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const {
    if (m_grid.channels == 1 || m_raw) return SampledSpectrum(eval_float(si));
    const Footprint f = footprint(si.p);
    SampledSpectrum out(0.0);
    for (int j = 0; j < f.count; ++j) {
        if (f.w[j] == 0) continue;
        const float* c = &m_coeffs[4 * f.voxel[j]];
        const std::array<double, 3> cd{c[0], c[1], c[2]};
        for (int k = 0; k < kSpectrumSamples; ++k) out[k] += f.w[j] * c[3] * sigmoid_polynomial(cd, wl[k]);
    }
    return out;
}

double GridVolumeTexture::eval_float(const SurfaceInteraction& si) const {
    const Footprint f = footprint(si.p);
    double v = 0;
    for (int j = 0; j < f.count; ++j) {
        const float* d = &m_grid.data[f.voxel[j] * size_t(m_grid.channels)];
        v += f.w[j] * (m_grid.channels == 1 ? double(d[0]) : RGB(d[0], d[1], d[2]).luminance());
    }
    return v;
}

RGB GridVolumeTexture::eval_rgb(const SurfaceInteraction& si) const {
    if (m_grid.channels == 1) return RGB(eval_float(si));
    const Footprint f = footprint(si.p);
    double r = 0, g = 0, b = 0;
    for (int j = 0; j < f.count; ++j) {
        const float* d = &m_grid.data[3 * f.voxel[j]];
        r += f.w[j] * d[0];
        g += f.w[j] * d[1];
        b += f.w[j] * d[2];
    }
    return RGB(r, g, b);
}

}  // namespace snell
