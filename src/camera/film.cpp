#include "camera/film.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
