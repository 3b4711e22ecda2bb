#include "core/rgb_to_spectrum_table.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace snell {

namespace {
double smoothstep(double x) { return x * x * (3.0 - 2.0 * x); }
}  // namespace

const RGBToSpectrumTable& RGBToSpectrumTable::reflectance() {
    static const RGBToSpectrumTable table;
    return table;
}

// Construction as in Jakob & Hanika's rgb2spec_opt: for the largest component `maxc` at value z
// and the other two at x z and y z, fit every (x, y) column along z, starting at a moderate z
// from grey by continuation and walking up and down from there, each fit warm-started from its
// neighbour (a few Levenberg-Marquardt steps). Fits integrate on a 5 nm grid.
RGBToSpectrumTable::RGBToSpectrumTable() : m_coeffs(size_t(3) * kRes * kRes * kRes * 3) {
    for (int k = 0; k < kRes; ++k) m_z[size_t(k)] = smoothstep(smoothstep(double(k) / (kRes - 1)));
    constexpr int kStride = 5;
    const int start = kRes / 5;
    tbb::parallel_for(0, 3 * kRes * kRes, [&](int job) {
        const int maxc = job / (kRes * kRes), yi = (job / kRes) % kRes, xi = job % kRes;
        const double x = double(xi) / (kRes - 1), y = double(yi) / (kRes - 1);
        auto rgb_at = [&](int zi) {
            const double z = m_z[size_t(zi)];
            double c[3];
            c[maxc] = z;
            c[(maxc + 1) % 3] = x * z;
            c[(maxc + 2) % 3] = y * z;
            return RGB(c[0], c[1], c[2]);
        };
        auto store = [&](int zi, const std::array<double, 3>& c) {
            float* out = at(maxc, zi, yi, xi);
            for (int i = 0; i < 3; ++i) out[i] = float(c[size_t(i)]);
        };
        std::array<double, 3> c0{};
        fit_reflectance_sigmoid(rgb_at(start), c0, false, kStride);
        store(start, c0);
        std::array<double, 3> c = c0;
        for (int zi = start + 1; zi < kRes; ++zi) {
            fit_reflectance_sigmoid(rgb_at(zi), c, true, kStride);
            store(zi, c);
        }
        c = c0;
        for (int zi = start - 1; zi >= 0; --zi) {
            fit_reflectance_sigmoid(rgb_at(zi), c, true, kStride);
            store(zi, c);
        }
    });
}

std::array<double, 3> RGBToSpectrumTable::operator()(const RGB& rgb_in) const {
    const double v[3] = {clamp(rgb_in.r, 0.0, 1.0), clamp(rgb_in.g, 0.0, 1.0), clamp(rgb_in.b, 0.0, 1.0)};
    if (v[0] == v[1] && v[1] == v[2]) {
        // sigmoid(c2) = v exactly; 0 and 1 give -inf and +inf, which the sigmoid maps to 0 and 1.
        const double g = v[0];
        if (g <= 0) return {0, 0, -INFINITY};
        if (g >= 1) return {0, 0, INFINITY};
        return {0, 0, (g - 0.5) / std::sqrt(g * (1 - g))};
    }
    const int maxc = (v[0] > v[1]) ? (v[0] > v[2] ? 0 : 2) : (v[1] > v[2] ? 1 : 2);
    const double z = v[maxc];
    const double x = v[(maxc + 1) % 3] * (kRes - 1) / z, y = v[(maxc + 2) % 3] * (kRes - 1) / z;
    const int xi = std::min(int(x), kRes - 2), yi = std::min(int(y), kRes - 2);
    const int zi =
        int(std::clamp<std::ptrdiff_t>(std::upper_bound(m_z.begin(), m_z.end(), z) - m_z.begin() - 1, 0, kRes - 2));
    const double dx = x - xi, dy = y - yi, dz = (z - m_z[size_t(zi)]) / (m_z[size_t(zi) + 1] - m_z[size_t(zi)]);
    std::array<double, 3> c{};
    for (int i = 0; i < 3; ++i) {
        auto co = [&](int a, int b, int d) { return double(at(maxc, zi + d, yi + b, xi + a)[i]); };
        auto lerp = [](double t, double p, double q) { return (1 - t) * p + t * q; };
        c[size_t(i)] = lerp(dz, lerp(dy, lerp(dx, co(0, 0, 0), co(1, 0, 0)), lerp(dx, co(0, 1, 0), co(1, 1, 0))),
                            lerp(dy, lerp(dx, co(0, 0, 1), co(1, 0, 1)), lerp(dx, co(0, 1, 1), co(1, 1, 1))));
    }
    return c;
}

}  // namespace snell
