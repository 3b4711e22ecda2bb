#include "camera/film.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/spectrum.h"

namespace snell {

namespace {

constexpr double kFloatMax = double(std::numeric_limits<float>::max());

/// The double as a float, clamped into float's finite range (NaN, which the renderer never
/// lets through, as 0).
float to_float(double v) {
    if (!(v == v)) return 0.0f;
    return float(std::clamp(v, -kFloatMax, kFloatMax));
}

}  // namespace

bool PixelSamples::ranks_above_largest(const Vec3& xyz, int t) const {
    if (!(xyz.y > 0)) return false;
    if (xyz.y != largest.y) return xyz.y > largest.y;
    if (xyz.x != largest.x) return xyz.x > largest.x;
    if (xyz.z != largest.z) return xyz.z > largest.z;
    return t > technique;
}

bool PixelSamples::add(const Vec3& xyz, int t) {
    const bool ok = sum.x.add(xyz.x) & sum.y.add(xyz.y) & sum.z.add(xyz.z);
    ++count;
    if (ranks_above_largest(xyz, t)) {
        largest = xyz;
        technique = t;
    }
    return ok;
}

void Film::merge(const Film& o) {
    if (o.m_w != m_w || o.m_h != m_h) throw std::invalid_argument("Film::merge: films of different sizes");
    for (int y = 0; y < m_h; ++y)
        for (int x = 0; x < m_w; ++x) {
            const size_t i = size_t(y) * m_w + x;
            add_samples(x, y, PixelSamples{o.m_sum[i], o.m_n[i], o.m_max_xyz[i], o.m_max_technique[i]});
        }
    for (int layer = 0; layer < o.splat_layers(); ++layer) {
        if (!o.has_splats(layer)) continue;
        if (size_t(layer) >= m_splats.size()) m_splats.resize(size_t(layer) + 1);
        auto& s = m_splats[size_t(layer)];
        if (s.empty()) s.resize(m_sum.size());
        for (size_t i = 0; i < s.size(); ++i) s[i] += o.m_splats[size_t(layer)][i];
    }
}

bool Film::same_samples(const Film& o) const {
    if (o.m_w != m_w || o.m_h != m_h || m_sum != o.m_sum || m_n != o.m_n || m_max_technique != o.m_max_technique)
        return false;
    for (size_t i = 0; i < m_max_xyz.size(); ++i)
        if (!(m_max_xyz[i] == o.m_max_xyz[i])) return false;
    const int layers = std::max(splat_layers(), o.splat_layers());
    for (int layer = 0; layer < layers; ++layer) {
        const bool a = has_splats(layer), b = o.has_splats(layer);
        if (!a && !b) continue;
        for (size_t i = 0; i < m_sum.size(); ++i) {
            const ExactSum3 zero;
            if (!((a ? m_splats[size_t(layer)][i] : zero) == (b ? o.m_splats[size_t(layer)][i] : zero))) return false;
        }
    }
    return true;
}

void Film::set_pixel(int x, int y, const ExactSum3& sum, uint64_t count, const Vec3& largest, int technique) {
    const size_t i = size_t(y) * m_w + x;
    m_sum[i] = sum;
    m_n[i] = count;
    m_max_xyz[i] = largest;
    m_max_y[i] = largest.y;
    m_max_technique[i] = int8_t(std::clamp(technique, -1, 127));
}

void Film::set_splat(int layer, int x, int y, const ExactSum3& sum) {
    if (size_t(layer) >= m_splats.size()) m_splats.resize(size_t(layer) + 1);
    auto& s = m_splats[size_t(layer)];
    if (s.empty()) s.resize(m_sum.size());
    s[size_t(y) * m_w + x] = sum;
}

void Film::fold_splat_layer(int layer, double scale) {
    if (!has_splats(layer) || layer == 0) return;
    for (int y = 0; y < m_h; ++y)
        for (int x = 0; x < m_w; ++x) {
            const Vec3 v = value(m_splats[size_t(layer)][size_t(y) * m_w + x]) * scale;
            if (v.x != 0 || v.y != 0 || v.z != 0) add_splat(x, y, v);
        }
    if (size_t(layer) + 1 == m_splats.size())
        m_splats.pop_back();
    else
        m_splats[size_t(layer)].clear();
}

std::vector<float> Film::to_linear_srgb(int layer) const {
    std::vector<float> rgb(size_t(m_w) * m_h * 3);
    for (int y = 0; y < m_h; ++y) {
        for (int x = 0; x < m_w; ++x) {
            // Convert the mean, not the sum: the XYZ -> sRGB map is linear, so this equals the
            // mean of per-sample sRGB while keeping unreached pixels at exactly zero.
            const Vec3 c = xyz_to_linear_srgb(layer == 0 ? xyz(x, y) : layer_xyz(layer, x, y));
            const size_t i = (size_t(y) * m_w + x) * 3;
            rgb[i + 0] = to_float(c.x);
            rgb[i + 1] = to_float(c.y);
            rgb[i + 2] = to_float(c.z);
        }
    }
    return rgb;
}

uint64_t Film::values_beyond_float(int layer) const {
    uint64_t n = 0;
    for (int y = 0; y < m_h; ++y)
        for (int x = 0; x < m_w; ++x) {
            const Vec3 c = xyz_to_linear_srgb(layer == 0 ? xyz(x, y) : layer_xyz(layer, x, y));
            for (double v : {c.x, c.y, c.z}) n += !(std::abs(v) <= kFloatMax);
        }
    return n;
}

PixelDominance pixel_dominance(const Film& film) {
    PixelDominance d;
    double total = 0, clamped = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const double c = film.clamped_y(x, y);
            total += film.sample_sum_y(x, y);
            clamped += c;
            d.clamped += c > 0;

            d.spread_radius = std::max(d.spread_radius, film.spread_radius_at(x, y));
            const double share = film.largest_sample_share(x, y);
            if (!(share > 0)) continue;
            ++d.pixels;
            d.max_share = std::max(d.max_share, share);
            // Beyond rounding: two equal pieces make a share of exactly one half.
            if (!(share > PixelDominance::kThreshold + 1e-9)) continue;
            ++d.dominated;
            if (const int t = film.largest_sample_technique(x, y); t >= 0) {
                if (size_t(t) >= d.dominated_by_technique.size()) d.dominated_by_technique.resize(size_t(t) + 1, 0);
                ++d.dominated_by_technique[size_t(t)];
            }
            double around = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if ((dx == 0 && dy == 0) || u < 0 || v < 0 || u >= film.width() || v >= film.height()) continue;
                    around += film.xyz(u, v).y;
                    ++n;
                }
            if (film.largest_contribution_y(x, y) > PixelDominance::kOutlierRatio * around / std::max(n, 1))
                ++d.outliers;
        }
    d.clamped_share = total > 0 ? clamped / total : 0.0;
    if (film.spread_radius() > 0) {
        d.spread_share = d.clamped_share * film.spread_delivered();
        d.spread_dropped = film.spread_cut_pixels();
    }
    return d;
}

}  // namespace snell
