#pragma once
// Helpers for statistical tests of whole renders: independent replicas (different seeds) of a
// small image, block means, and z-tests between two estimators with a Bonferroni correction.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "loader/scene_loader.h"
#include "manifold/walk_counters.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace snell::test {

/// Loads an XML scene given as a string (relative paths resolve to the repo root).
inline LoadedScene load_xml(const std::string& xml, const Defines& d = {}) {
    return load_scene_string(xml, "test-scene", SNELL_SOURCE_DIR, d);
}

/// One render of `spp` samples with `seed`, as linear sRGB floats.
inline std::vector<float> render_rgb(const LoadedScene& ls, int spp, uint64_t seed = 0) {
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.progress = false;
    return render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb();
}

/// Every value of the film's image is finite and the image is not black.
inline void expect_finite_and_lit(const Film& film) {
    double sum = 0;
    for (float v : film.to_linear_srgb()) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0);
}

/// Mean and standard error of a quantity over independent replicas.
struct Estimate {
    double mean = 0, stderr_ = 0;
    int n = 0;  ///< replicas
};

/// Regularised incomplete beta I_x(a, b) by Lentz's continued fraction (converges for
/// x < (a + 1) / (a + b + 2); the symmetry I_x(a,b) = 1 - I_{1-x}(b,a) covers the rest).
inline double incomplete_beta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    if (x > (a + 1) / (a + b + 2)) return 1 - incomplete_beta(b, a, 1 - x);
    const double log_front =
        std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    const double tiny = 1e-300;
    double f = 1, c = 1, d = 0;
    for (int i = 0; i <= 400; ++i) {
        const int m = i / 2;
        double num;
        if (i == 0)
            num = 1;
        else if (i % 2 == 0)
            num = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
        else
            num = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
        d = 1 + num * d;
        if (std::abs(d) < tiny) d = tiny;
        d = 1 / d;
        c = 1 + num / c;
        if (std::abs(c) < tiny) c = tiny;
        const double cd = c * d;
        f *= cd;
        if (std::abs(1 - cd) < 1e-14) break;
    }
    return std::exp(log_front) * (f - 1) / a;
}

/// Two-sided tail probability P(|T| > t) of Student's t with nu degrees of freedom.
inline double student_t_two_sided_p(double t, double nu) { return incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t)); }

/// Welch's two-sample t-test of equal means; returns the two-sided p-value.
inline double welch_p_value(const Estimate& a, const Estimate& b) {
    const double va = a.stderr_ * a.stderr_, vb = b.stderr_ * b.stderr_;
    const double diff = std::abs(a.mean - b.mean);
    if (va + vb == 0) return diff <= 1e-12 * std::max(std::abs(a.mean), std::abs(b.mean)) ? 1.0 : 0.0;
    const double t = diff / std::sqrt(va + vb);
    const double nu = sqr(va + vb) / (va * va / (a.n - 1) + vb * vb / (b.n - 1));
    return student_t_two_sided_p(t, nu);
}

/// Block-averaged linear sRGB luminance (or one channel) of `replicas` independent renders.
/// Returns per block the mean and standard error across replicas.
inline std::vector<Estimate> block_estimates(const LoadedScene& ls, const Integrator& integ, int spp, int replicas,
                                             int block, uint64_t seed_base, int channel = -1) {
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
        out.push_back({m, std::sqrt(var / double(v.size())), int(v.size())});
    }
    return out;
}

/// Whole-image mean from the blocks of block_estimates(): pixels draw from independent random
/// streams, so block means of one replica are independent and the variances add.
inline Estimate whole_image(const std::vector<Estimate>& blocks) {
    Estimate e;
    double var = 0;
    for (const Estimate& b : blocks) e.mean += b.mean, var += b.stderr_ * b.stderr_;
    const double nb = double(blocks.size());
    e.mean /= nb;
    e.stderr_ = std::sqrt(var) / nb;
    e.n = blocks.front().n;
    return e;
}

/// Expects that two independent estimators agree per block: Welch's t-test per block (the
/// standard errors come from few replicas, so Student's t, not the normal), with a
/// Bonferroni correction over the blocks at family-wise level alpha.
inline void expect_agreement(const std::vector<Estimate>& a, const std::vector<Estimate>& b, double alpha,
                             const char* what) {
    ASSERT_EQ(a.size(), b.size());
    const double threshold = alpha / double(a.size());
    int failures = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double p = welch_p_value(a[i], b[i]);
        if (p < threshold) {
            if (++failures <= 5)
                ADD_FAILURE() << what << ": block " << i << " differs: " << a[i].mean << " +- " << a[i].stderr_
                              << " vs " << b[i].mean << " +- " << b[i].stderr_ << " (p = " << p << " < " << threshold
                              << ")";
        }
    }
    EXPECT_EQ(failures, 0) << what;
}

/// Number of blocks where the two estimators differ at family-wise level alpha.
inline int count_disagreements(const std::vector<Estimate>& a, const std::vector<Estimate>& b, double alpha) {
    int n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += welch_p_value(a[i], b[i]) < alpha / double(a.size());
    return n;
}

/// The learned allocation's choice in a render of `spp` samples per pixel (its pilot's
/// included): how many regions took each q (0, 1/64 .. 1; walk_counters::allocation_regions),
/// printed as "[what] regions by q ...".
inline std::vector<uint64_t> allocation_regions(const LoadedScene& ls, int spp, const std::string& what) {
    RenderOptions opt;
    opt.spp = spp;
    opt.progress = false;
    const std::vector<uint64_t> regions =
        render(*ls.scene, *ls.integrator, ls.film, opt).counters.bins(walk_counters::allocation_regions);
    std::string chosen;
    for (uint64_t n : regions) chosen += " " + std::to_string(n);
    std::cout << "[" << what << "] regions by q (0, 1/64 .. 1):" << chosen << "\n";
    return regions;
}

}  // namespace snell::test
