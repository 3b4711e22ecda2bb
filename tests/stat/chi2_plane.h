#pragma once
// Chi-square goodness-of-fit test of a sampler of points in the plane (pixel filter offsets,
// planar warps) against its claimed density, by the method of chi2.h:
//   1. the rectangle [lo, hi] is cut into res_x x res_y equal bins;
//   2. the claimed pdf (per unit area) is integrated over each bin by nested adaptive Simpson;
//   3. `samples` points are drawn and histogrammed; points outside the rectangle (or failed
//      samples) go into an extra cell whose expectation is N (1 - integral of the pdf), which
//      also checks the pdf's normalisation;
//   4. cells expecting fewer than min_expected samples are pooled; Pearson's statistic gives a
//      p-value, rejected below the Sidak-corrected significance.
#include "stat/chi2.h"

namespace snell::test {

struct Chi2PlaneOptions {
    int res_x = 40, res_y = 40;     ///< bins along x and y
    size_t samples = 1000000;       ///< points drawn
    double min_expected = 5.0;      ///< pool cells expecting fewer samples than this
    double significance = 0.01;     ///< per-family false-rejection rate
    int test_count = 1;             ///< chi-square tests in the family (Sidak correction)
    double integration_eps = 1e-9;  ///< absolute quadrature tolerance per bin (probability)
    uint64_t seed = 7;
};

/// `sample(rng)` returns a point or std::nullopt; `pdf(p)` is the claimed density per unit area.
/// `observed` / `expected` in the result are row-major (y, x).
inline Chi2Result chi2_plane_test(const std::function<std::optional<Vec2>(PCG32&)>& sample,
                                  const std::function<double(const Vec2&)>& pdf, const Vec2& lo, const Vec2& hi,
                                  const Chi2PlaneOptions& opt = {}) {
    const int nx = opt.res_x, ny = opt.res_y, nbins = nx * ny;
    const double dx = (hi.x - lo.x) / nx, dy = (hi.y - lo.y) / ny;
    Chi2Result res;
    res.observed.assign(size_t(nbins), 0.0);
    res.expected.assign(size_t(nbins), 0.0);

    PCG32 rng(opt.seed, 0x5eed);
    size_t outside = 0;
    for (size_t i = 0; i < opt.samples; ++i) {
        const auto p = sample(rng);
        if (!p) {
            ++outside;
            continue;
        }
        const double fx = (p->x - lo.x) / dx, fy = (p->y - lo.y) / dy;
        if (!(fx >= 0 && fx <= nx && fy >= 0 && fy <= ny)) {
            ++outside;
            continue;
        }
        ++res.valid_samples;
        const int ix = std::min(nx - 1, int(fx)), iy = std::min(ny - 1, int(fy));
        res.observed[size_t(iy * nx + ix)] += 1;
    }

    auto eval_pdf = [&](double x, double y) {
        const double v = pdf(Vec2(x, y));
        return std::isfinite(v) ? v : 0.0;
    };
    double total = 0;
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix) {
            const double x0 = lo.x + ix * dx, y0 = lo.y + iy * dy;
            auto inner = [&](double y) {
                return adaptive_simpson([&](double x) { return eval_pdf(x, y); }, x0, x0 + dx, opt.integration_eps / dy,
                                        2);
            };
            const double v = adaptive_simpson(inner, y0, y0 + dy, opt.integration_eps, 2);
            res.expected[size_t(iy * nx + ix)] = v * double(opt.samples);
            total += v;
        }
    res.pdf_integral = total;

    std::vector<std::pair<double, double>> cells;  // (expected, observed)
    for (int i = 0; i < nbins; ++i) cells.push_back({res.expected[size_t(i)], res.observed[size_t(i)]});
    cells.push_back({std::max(0.0, 1 - total) * double(opt.samples), double(outside)});
    const std::vector<std::pair<double, double>> pooled = pool_cells(std::move(cells), opt.min_expected);
    if (pooled.size() < 2) {
        res.message = "fewer than two cells after pooling";
        return res;
    }
    std::ostringstream msg;
    pearson_test(pooled, opt.significance, opt.test_count, res, msg);
    msg << "chi2 = " << res.chi2 << ", dof = " << res.dof << ", p = " << res.p_value << " (threshold " << res.threshold
        << "), pdf integral = " << total << ", outside = " << outside << "/" << opt.samples;
    if (!res.passed) {
        std::vector<int> idx(static_cast<size_t>(nbins));
        std::iota(idx.begin(), idx.end(), 0);
        auto dev = [&](int i) {
            const double e = res.expected[size_t(i)], o = res.observed[size_t(i)];
            return e > 0 ? sqr(o - e) / e : (o > 0 ? kInfinity : 0.0);
        };
        std::sort(idx.begin(), idx.end(), [&](int a, int b) { return dev(a) > dev(b); });
        msg << "\n  worst bins (x, y: observed / expected):";
        for (int k = 0; k < std::min(nbins, 6); ++k)
            msg << "\n    (" << idx[size_t(k)] % nx << ", " << idx[size_t(k)] / nx
                << "): " << res.observed[size_t(idx[size_t(k)])] << " / " << res.expected[size_t(idx[size_t(k)])];
    }
    res.message = msg.str();
    return res;
}

}  // namespace snell::test
