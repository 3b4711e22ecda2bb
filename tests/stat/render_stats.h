#pragma once
// Helpers for statistical tests of whole renders: independent replicas (different seeds) of a
// small image, block means, and z-tests between two estimators with a Bonferroni correction.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "integrators/integrator.h"
#include "io/scene_loader.h"
#include "render/renderer.h"

namespace snell::test {

/// Loads an XML scene given as a string (relative paths resolve to the repo root).
inline LoadedScene load_xml(const std::string& xml, const Defines& d = {}) {
    return load_scene_string(xml, "test-scene", SNELL_SOURCE_DIR, d);
}

/// Mean and standard error of a quantity over independent replicas.
struct Estimate {
    double mean = 0, stderr_ = 0;
};

/// Block-averaged linear sRGB luminance (or one channel) of `replicas` independent renders.
/// Returns per block the mean and standard error across replicas.
inline std::vector<Estimate> block_estimates(const LoadedScene& ls, const Integrator& integ, int spp,
                                             int replicas, int block, uint64_t seed_base, int channel = -1) {
    const int w = ls.film.out_width(), h = ls.film.out_height();
    const int bw = (w + block - 1) / block, bh = (h + block - 1) / block;
    std::vector<std::vector<double>> values(size_t(bw * bh));
    for (int r = 0; r < replicas; ++r) {
        RenderOptions opt;
        opt.spp = spp;
        opt.seed = seed_base + uint64_t(r) * 7919;
        opt.progress = false;
        const RenderResult res = render(*ls.scene, integ, ls.film, opt);
        const std::vector<float> rgb = res.film.to_linear_srgb();
        std::vector<double> sum(size_t(bw * bh), 0.0), cnt(size_t(bw * bh), 0.0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* p = &rgb[(size_t(y) * w + x) * 3];
                const double v = channel < 0 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[channel];
                const size_t b = size_t((y / block) * bw + x / block);
                sum[b] += v;
                cnt[b] += 1;
            }
        for (size_t b = 0; b < sum.size(); ++b) values[b].push_back(sum[b] / cnt[b]);
    }
    std::vector<Estimate> out;
    for (auto& v : values) {
        double m = 0;
        for (double x : v) m += x;
        m /= double(v.size());
        double var = 0;
        for (double x : v) var += (x - m) * (x - m);
        var /= double(v.size() - 1);
        out.push_back({m, std::sqrt(var / double(v.size()))});
    }
    return out;
}

/// Two-sided normal quantile for a Bonferroni-corrected family of `n` tests at level alpha.
inline double bonferroni_z(double alpha, size_t n) {
    // Bisection on the normal tail: P(|Z| > z) = alpha / n.
    const double target = alpha / double(n);
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (std::erfc(mid / std::sqrt(2.0)) > target) lo = mid; else hi = mid;
    }
    return 0.5 * (lo + hi);
}

/// Expects that two independent estimators agree per block within their joint standard error.
/// Blocks whose both estimates have zero variance must agree exactly.
inline void expect_agreement(const std::vector<Estimate>& a, const std::vector<Estimate>& b, double alpha,
                             const char* what) {
    ASSERT_EQ(a.size(), b.size());
    const double z = bonferroni_z(alpha, a.size());
    int failures = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double se = std::sqrt(a[i].stderr_ * a[i].stderr_ + b[i].stderr_ * b[i].stderr_);
        const double diff = std::abs(a[i].mean - b[i].mean);
        if (diff > z * se + 1e-12 * std::max(a[i].mean, b[i].mean)) {
            if (++failures <= 5)
                ADD_FAILURE() << what << ": block " << i << " differs: " << a[i].mean << " +- " << a[i].stderr_ << " vs "
                              << b[i].mean << " +- " << b[i].stderr_ << " (z threshold " << z << ")";
        }
    }
    EXPECT_EQ(failures, 0) << what;
}

}  // namespace snell::test
