#pragma once
// Per-block and whole-image luminance of independent replicas of a small render, and a
// Bonferroni-corrected Welch comparison of two such estimators. Per-block tests catch errors
// confined to a region (one object, one light); the whole-image test catches small errors
// spread over everything (a MIS weight a few percent off), which no single block resolves.
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "stat/render_stats.h"

namespace snell::test {

/// Replicas per estimator: Welch dof ~ 20, so Student's t tails stay close to normal ones.
constexpr int kAgreementReplicas = 12;

/// Linear sRGB luminance (= CIE Y) per block and over the whole image. Luminance, not R, G, B:
/// with one wavelength per path a single sample's R, G and B carry large colour-matching
/// noise of both signs; its Y much less.
struct ReplicaStats {
    std::vector<Estimate> blocks;
    Estimate image;
};

/// Mean and standard error of the mean of independent values.
inline Estimate estimate_of(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m += x;
    m /= double(v.size());
    double var = 0;
    for (double x : v) var += (x - m) * (x - m);
    var /= double(v.size() - 1);
    return {m, std::sqrt(var / double(v.size())), int(v.size())};
}

/// Statistics of `replicas` independent images produced by render_seed(seed) for seeds
/// seed_base + 7919 r: block x block pixel means and the image mean.
inline ReplicaStats replica_stats_of(const LoadedScene& ls, int block, uint64_t seed_base, int replicas,
                                     const std::function<RenderResult(uint64_t)>& render_seed) {
    const int w = ls.film.out_width(), h = ls.film.out_height();
    const int bw = (w + block - 1) / block, bh = (h + block - 1) / block;
    std::vector<std::vector<double>> blocks(size_t(bw * bh));
    std::vector<double> image;
    for (int r = 0; r < replicas; ++r) {
        const std::vector<float> rgb = render_seed(seed_base + uint64_t(r) * 7919).film.to_linear_srgb();
        std::vector<double> bsum(blocks.size(), 0.0), bcnt(blocks.size(), 0.0);
        double total = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* p = &rgb[(size_t(y) * w + x) * 3];
                const double lum = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                const size_t b = size_t((y / block) * bw + x / block);
                bsum[b] += lum;
                bcnt[b] += 1;
                total += lum;
            }
        for (size_t b = 0; b < blocks.size(); ++b) blocks[b].push_back(bsum[b] / bcnt[b]);
        image.push_back(total / double(w * h));
    }
    ReplicaStats s;
    for (auto& v : blocks) s.blocks.push_back(estimate_of(v));
    s.image = estimate_of(image);
    return s;
}

/// replica_stats_of() for the scene's own integrator at `spp` through the tiled renderer.
inline ReplicaStats replica_stats(const LoadedScene& ls, int spp, int block, uint64_t seed_base,
                                  int replicas = kAgreementReplicas) {
    return replica_stats_of(ls, block, seed_base, replicas, [&](uint64_t seed) {
        RenderOptions opt;
        opt.spp = spp;
        opt.seed = seed;
        opt.progress = false;
        opt.tile_size = 8;  // enough tiles for every core on these small images
        return render(*ls.scene, *ls.integrator, ls.film, opt);
    });
}

/// Welch's t-test per block and for the whole image, Bonferroni-corrected over all of them at
/// family-wise level alpha. Returns the number of rejections; reports them when `report`.
inline int disagreements(const ReplicaStats& a, const ReplicaStats& b, double alpha, bool report) {
    std::vector<Estimate> ea = a.blocks, eb = b.blocks;
    ea.push_back(a.image);
    eb.push_back(b.image);
    const double threshold = alpha / double(ea.size());
    int n = 0;
    for (size_t i = 0; i < ea.size(); ++i) {
        const double p = welch_p_value(ea[i], eb[i]);
        if (p >= threshold) continue;
        ++n;
        if (report && n <= 6) {
            const std::string what = i < a.blocks.size() ? "block " + std::to_string(i) : "whole image";
            ADD_FAILURE() << what << " differs: " << ea[i].mean << " +- " << ea[i].stderr_ << " vs " << eb[i].mean
                          << " +- " << eb[i].stderr_ << " (p = " << p << " < " << threshold << ")";
        }
    }
    return n;
}

/// Expects agreement at family-wise level 0.01 and prints both whole-image estimates.
inline void expect_replicas_agree(const ReplicaStats& a, const ReplicaStats& b, const char* what) {
    std::printf("%s: whole image %.5f +- %.5f vs %.5f +- %.5f\n", what, a.image.mean, a.image.stderr_, b.image.mean,
                b.image.stderr_);
    EXPECT_EQ(disagreements(a, b, 0.01, true), 0) << what;
}

}  // namespace snell::test
