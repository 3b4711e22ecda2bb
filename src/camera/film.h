#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/exact_sum.h"
#include "core/vector.h"

namespace snell {

/// The samples one pixel received in one piece of work (a pass of a tile, say): their exact sum,
/// their count and the largest of them. Film::add_samples adds it; any grouping of a pixel's
/// samples into such pieces, in any order, gives the same film (issue 27).
struct PixelSamples {
    ExactSum3 sum;
    uint64_t count = 0;
    Vec3 largest;        ///< the sample of largest luminance (Y) so far (zero: none positive)
    int technique = -1;  ///< the technique that delivered it
    /// Adds one sample (its XYZ, already filter-weighted) delivered by `technique`. Returns false
    /// when a component was beyond ExactSum's range and was saturated.
    bool add(const Vec3& xyz, int technique);
    /// True when sample (xyz, technique) ranks above the current largest: by luminance, then by
    /// X, Z and technique, a total order, so that the largest does not depend on the order.
    bool ranks_above_largest(const Vec3& xyz, int technique) const;
};

/// The outlier clamp a film is shown with (apply_outlier_clamp, camera/outlier_clamp.h, fills it
/// in after the last sample): the share a pixel's largest sample may carry (0: off) and, with a
/// spread radius, the light it took spread over neighbours.
struct OutlierClamp {
    double max_share = 0;
    int spread_radius = 0;
    std::vector<Vec3> spread;         ///< light added per pixel (a mean; empty without spread)
    std::vector<double> piece_y;      ///< the largest piece of one spread sample among it (Y, a mean)
    std::vector<uint8_t> radius;      ///< per clamped pixel, the radius its light was spread over
    uint64_t cut_pixels = 0;          ///< pixels where spread light was cut
    double taken_y = 0, given_y = 0;  ///< light spread (means), and delivered
};

/// Accumulates XYZ per pixel, exactly (ExactSum), so that the film does not depend on the order
/// in which threads, ranks or merged partial films add their samples (issue 27) (box filter: each sample lands in the
/// pixel it was taken in). Sample weights are counted per pixel so a partially rendered (interrupted or time-limited)
/// film still resolves to an unbiased average for the pixels it reached.
/// A second, unnormalised layer holds splats (contributions of light paths that reach the
/// film anywhere: BDPT's light tracing, ERPT's deposits); it is scaled by `splat_scale`
/// (1 / camera samples per pixel) and added to the pixel mean. Further splat layers are debug
/// images (BDPT's per-strategy contributions) that are not part of the image.
class Film {
public:
    Film(int width, int height)
        : m_w(width),
          m_h(height),
          m_sum(size_t(width) * height),
          m_n(size_t(width) * height, 0),
          m_max_y(size_t(width) * height, 0.0),
          m_max_xyz(size_t(width) * height),
          m_max_technique(size_t(width) * height, -1) {}
    int width() const { return m_w; }
    int height() const { return m_h; }
    void add(int x, int y, const Vec3& xyz) { add_sum(x, y, xyz, 1, xyz); }
    /// Adds `count` samples at once (whole-pixel sums from a tile); `largest` is the one of
    /// them with the largest luminance (Y); its XYZ is kept for max_sample_share, and the
    /// technique that delivered it (SampleTracer::technique_names index, -1: unknown) for the
    /// dominance statistics. The sum is one exact term: sums of the same samples grouped
    /// otherwise may differ in their last bits; add_samples does not.
    void add_sum(int x, int y, const Vec3& xyz_sum, uint64_t count, const Vec3& largest = Vec3(), int technique = -1) {
        PixelSamples p;
        p.sum.x.add(xyz_sum.x);
        p.sum.y.add(xyz_sum.y);
        p.sum.z.add(xyz_sum.z);
        p.count = count;
        if (p.ranks_above_largest(largest, technique)) {
            p.largest = largest;
            p.technique = technique;
        }
        add_samples(x, y, p);
    }
    /// Adds a pixel's samples (exact: any grouping of them gives the same film).
    void add_samples(int x, int y, const PixelSamples& p) {
        const size_t i = size_t(y) * m_w + x;
        m_sum[i] += p.sum;
        m_n[i] += p.count;
        if (PixelSamples{{}, 0, m_max_xyz[i], m_max_technique[i]}.ranks_above_largest(p.largest, p.technique)) {
            m_max_y[i] = p.largest.y;
            m_max_xyz[i] = p.largest;
            m_max_technique[i] = int8_t(std::clamp(p.technique, -1, 127));
        }
    }
    /// Adds another film of the same size (a rank's, a partial render's): samples, counts,
    /// largest samples and splats. Exact, so merging in any order gives the same film. The
    /// outlier clamp and the splat scale are not merged: set them on the result.
    void merge(const Film& other);
    /// True when every accumulated value (sums, counts, largest samples, splats) is the same.
    bool same_samples(const Film& other) const;

    /// The exact sums of the pixel's samples, its largest sample and that sample's technique,
    /// and a splat layer's exact sums (partial films, render/partial_film.h).
    const ExactSum3& exact_sum(int x, int y) const { return m_sum[size_t(y) * m_w + x]; }
    Vec3 largest_sample_xyz(int x, int y) const { return m_max_xyz[size_t(y) * m_w + x]; }
    int splat_layers() const { return int(m_splats.size()); }
    bool has_splats(int layer) const { return size_t(layer) < m_splats.size() && !m_splats[size_t(layer)].empty(); }
    const ExactSum3& exact_splat(int layer, int x, int y) const { return m_splats[size_t(layer)][size_t(y) * m_w + x]; }
    /// Sets a pixel's accumulated values (a partial film read back).
    void set_pixel(int x, int y, const ExactSum3& sum, uint64_t count, const Vec3& largest, int technique);
    void set_splat(int layer, int x, int y, const ExactSum3& sum);
    /// Adds `scale` times splat layer `layer` (>= 1) to layer 0, pixel by pixel, and removes the
    /// layer: a part of the splats whose scale is known only when every sample is in (hslt's
    /// chain splats, scaled by the refined normalisation). Deterministic: the same exact sums
    /// give the same image.
    void fold_splat_layer(int layer, double scale);

    /// The outlier clamp the film's value is shown with (camera/outlier_clamp.h computes it, as
    /// a post-process of the finished film; the samples are not changed).
    void set_outlier_clamp(OutlierClamp clamp) { m_clamp = std::move(clamp); }
    double max_sample_share() const { return m_clamp.max_share; }
    int spread_radius() const { return m_clamp.spread_radius; }
    /// The luminance (Y) the clamp removes from the pixel's sample sum (0 when it is off).
    double clamped_y(int x, int y) const {
        const size_t i = size_t(y) * m_w + x;
        const double sum_y = m_sum[i].y.value();
        const double s = m_clamp.max_share;
        if (!(s > 0) || m_n[i] < 2 || !(sum_y > 0)) return 0;
        const double cap = s / (1 - s) * std::max(0.0, sum_y - m_max_y[i]);
        return std::max(0.0, m_max_y[i] - cap);
    }
    uint64_t samples(int x, int y) const { return m_n[size_t(y) * m_w + x]; }
    /// The share of the pixel's luminance that its largest single contribution carries (0 when
    /// the pixel is black): near 1 / samples in a converging pixel, near 1 when one sample (a
    /// firefly) makes the pixel. A contribution is one of the pixel's samples or, with the
    /// clamp's spread, the piece of one other pixel's clamped sample. Splats are not samples of
    /// a pixel and are left out. With max_sample_share, the share after the clamp (at most that
    /// share, for the pixel's own samples and for spread pieces alike).
    double largest_sample_share(int x, int y) const {
        const size_t i = size_t(y) * m_w + x;
        if (!m_n[i]) return 0;
        const double n = double(m_n[i]), c = clamped_y(x, y);
        const double total = (m_sum[i].y.value() - c) / n + (m_clamp.spread.empty() ? 0.0 : m_clamp.spread[i].y);
        // As means (a piece is one), so that a piece at exactly the share does not round above it.
        const double largest = std::max((m_max_y[i] - c) / n, m_clamp.piece_y.empty() ? 0.0 : m_clamp.piece_y[i]);
        return total > 0 ? std::min(1.0, largest / total) : 0.0;
    }
    /// The summed luminance (Y) of the pixel's own samples (before any clamp; no splats).
    double sample_sum_y(int x, int y) const { return m_sum[size_t(y) * m_w + x].y.value(); }
    /// The summed XYZ of the pixel's own samples (before any clamp; no splats).
    Vec3 sample_sum(int x, int y) const { return value(m_sum[size_t(y) * m_w + x]); }
    /// The largest luminance (Y) one of the pixel's samples carried (before any clamp).
    double largest_sample_y(int x, int y) const { return m_max_y[size_t(y) * m_w + x]; }
    /// The largest contribution to the pixel after the clamp, as a sample's luminance (the
    /// pixel's mean is the sum of these over its sample count): its largest own sample, clamped,
    /// or the largest piece of a spread sample, whichever is larger.
    double largest_contribution_y(int x, int y) const {
        const size_t i = size_t(y) * m_w + x;
        const double own = m_max_y[i] - clamped_y(x, y);
        return m_clamp.piece_y.empty() ? own : std::max(own, m_clamp.piece_y[i] * double(m_n[i]));
    }
    /// The technique that delivered the pixel's largest sample (-1: not known). (With a share
    /// of at most 0.5, the biased mode's, a spread piece never dominates a pixel:
    /// apply_outlier_clamp widens its disc or drops it.)
    int largest_sample_technique(int x, int y) const { return m_max_technique[size_t(y) * m_w + x]; }
    /// The light the clamp's spread added to the pixel (XYZ, a mean; 0 without spread).
    Vec3 spread_xyz(int x, int y) const {
        return m_clamp.spread.empty() ? Vec3() : m_clamp.spread[size_t(y) * m_w + x];
    }
    /// Of the light the clamp took (as pixel means), the share the spread delivered (1 when no
    /// pixel's pieces had to be cut), and the pixels where pieces were cut.
    double spread_delivered() const { return m_clamp.taken_y > 0 ? m_clamp.given_y / m_clamp.taken_y : 1.0; }
    uint64_t spread_cut_pixels() const { return m_clamp.cut_pixels; }
    /// The radius the clamped light of this pixel was spread over (0: not spread).
    int spread_radius_at(int x, int y) const {
        return m_clamp.radius.empty() ? 0 : m_clamp.radius[size_t(y) * m_w + x];
    }
    /// Adds a splat to `layer` (0: the image, k > 0: debug layer k).
    void add_splat(int x, int y, const Vec3& xyz, int layer = 0) {
        if (size_t(layer) >= m_splats.size()) m_splats.resize(size_t(layer) + 1);
        auto& s = m_splats[size_t(layer)];
        if (s.empty()) s.resize(m_sum.size());
        ExactSum3& t = s[size_t(y) * m_w + x];
        t.x.add(xyz.x);
        t.y.add(xyz.y);
        t.z.add(xyz.z);
    }
    void set_splat_scale(double scale) { m_splat_scale = scale; }
    double splat_scale() const { return m_splat_scale; }
    /// Pixel value: mean XYZ of the pixel's own samples (zero if none) plus its scaled splats.
    Vec3 xyz(int x, int y) const {
        const size_t i = size_t(y) * m_w + x;
        Vec3 sum = value(m_sum[i]);
        if (const double c = clamped_y(x, y); c > 0) sum -= m_max_xyz[i] * (c / m_max_y[i]);
        Vec3 v = m_n[i] ? sum / double(m_n[i]) : Vec3();
        if (!m_clamp.spread.empty()) v += m_clamp.spread[i];
        if (!m_splats.empty() && !m_splats[0].empty()) v += value(m_splats[0][i]) * m_splat_scale;
        return v;
    }
    /// Scaled splats of debug layer `layer` (>= 1).
    Vec3 layer_xyz(int layer, int x, int y) const {
        if (size_t(layer) >= m_splats.size() || m_splats[size_t(layer)].empty()) return Vec3();
        return value(m_splats[size_t(layer)][size_t(y) * m_w + x]) * m_splat_scale;
    }
    /// Linear sRGB image, row-major, 3 floats per pixel (layer 0: the image). A value beyond
    /// float's range (a finite double pixel can be: radiance 1e300) becomes the largest float of
    /// its sign, never Inf (issue 12); values_beyond_float() counts them.
    std::vector<float> to_linear_srgb(int layer = 0) const;
    /// How many values of layer `layer`'s linear sRGB exceed float's range (clamped on output).
    uint64_t values_beyond_float(int layer = 0) const;

private:
    int m_w, m_h;
    static Vec3 value(const ExactSum3& s) { return {s.x.value(), s.y.value(), s.z.value()}; }
    std::vector<ExactSum3> m_sum;
    std::vector<uint64_t> m_n;
    std::vector<double> m_max_y;                   // largest single-sample luminance per pixel
    std::vector<Vec3> m_max_xyz;                   // that sample's XYZ
    std::vector<int8_t> m_max_technique;           // and its technique (-1: unknown)
    OutlierClamp m_clamp;                          // set_outlier_clamp (apply_outlier_clamp)
    std::vector<std::vector<ExactSum3>> m_splats;  // per layer; empty until first splat
    double m_splat_scale = 0;
};

/// How far single samples dominate pixels (issue 10: "no single sample may dominate a pixel").
struct PixelDominance {
    /// A pixel is dominated when one sample carries more than this share of its luminance.
    static constexpr double kThreshold = 0.5;
    uint64_t pixels = 0;     ///< pixels with a positive luminance sum
    uint64_t dominated = 0;  ///< of those, pixels whose largest sample carries > kThreshold
    double max_share = 0;    ///< the largest share of any pixel
    /// A dominated pixel is dominated by an outlier when its largest sample also exceeds this
    /// many times the mean luminance of its (up to) eight neighbours. A pixel at a sharp
    /// caustic's edge, where one of its samples lands in the caustic, is dominated by that
    /// sample, but the sample is no brighter than the lit pixels beside it; a firefly is.
    static constexpr double kOutlierRatio = 10;
    uint64_t outliers = 0;  ///< dominated pixels whose largest sample is an outlier
    /// Dominated pixels by the technique of their largest sample (Film::largest_sample_technique
    /// as the index; pixels with an unknown technique are not counted here).
    std::vector<uint64_t> dominated_by_technique;
    /// With Film::max_sample_share: pixels whose largest sample the clamp scaled down, and the
    /// share of the image's (camera-sample) luminance it removed: the clamp's bias.
    uint64_t clamped = 0;
    double clamped_share = 0;
    /// With spread_radius: the share of the image's luminance spread back over neighbours (the
    /// light lost is clamped_share - spread_share), the widest disc used, and the pixels where
    /// spread light was cut because no disc hid its source (outlier_clamp.cpp).
    double spread_share = 0;
    int spread_radius = 0;
    uint64_t spread_dropped = 0;
};
/// Film::largest_sample_share over the film's pixels.
PixelDominance pixel_dominance(const Film& film);

}  // namespace snell
