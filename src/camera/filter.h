#pragma once
// Pixel reconstruction filters (Mitsuba 3's `box`, `tent`, `gaussian`), used by filter
// importance sampling: a camera sample of pixel (px, py) is taken at raster position
// (px + 0.5, py + 0.5) + offset with offset ~ pdf, and its radiance is multiplied by
// f(offset) / pdf(offset), so the pixel estimates the filter-weighted integral
//   I(px, py) = integral of f(offset) L(centre + offset) d offset
// and every sample lands in exactly one pixel. Splats (light tracing) estimate the same integral
// by spreading a contribution at raster position p over the pixels whose support holds p, with
// weights f(p - centre) (for_each_pixel_in_support).
//
// Every filter is separable, f(x, y) = f1(x) f1(y), and normalised: its integral over the
// plane is 1 (Mitsuba leaves its filters unnormalised and divides by the weight sum instead).
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "core/vector.h"

namespace snell {

/// Result of filter importance sampling: an offset from the pixel centre (pixels) and the
/// weight f(offset) / pdf(offset) the sample's radiance is multiplied by (1 for exact sampling).
struct FilterSample {
    Vec2 offset;
    double weight = 1;
};

/// Pixel reconstruction filter, normalised so that its integral over the plane is 1.
/// Offsets are in pixels, x right and y down (raster convention); the support is the
/// rectangle [-radius.x, radius.x] x [-radius.y, radius.y].
class Filter {
public:
    virtual ~Filter() = default;
    /// Support half-widths (pixels).
    virtual Vec2 radius() const = 0;
    /// Normalised filter value at `offset` from the pixel centre (per pixel^2); 0 outside the support.
    virtual double eval(const Vec2& offset) const = 0;
    /// Maps u in [0,1)^2 to an offset within the support, deterministically.
    virtual FilterSample sample(const Vec2& u) const = 0;
    /// Density of sample()'s offsets (per pixel^2).
    virtual double pdf(const Vec2& offset) const = 0;
    /// Mitsuba plugin name: "box", "tent" or "gaussian".
    virtual std::string name() const = 0;
};

/// Mitsuba 3's `box`: 1 on the pixel, [-0.5, 0.5)^2 (half-open, so a raster position on a pixel
/// edge belongs to exactly one pixel). Sampled exactly: offset = u - 0.5, weight 1.
class BoxFilter final : public Filter {
public:
    Vec2 radius() const override { return {0.5, 0.5}; }
    double eval(const Vec2& offset) const override;
    FilterSample sample(const Vec2& u) const override;
    double pdf(const Vec2& offset) const override { return eval(offset); }
    std::string name() const override { return "box"; }
};

/// Mitsuba 3's `tent`: f1(x) = max(0, 1 - |x| / r) / r with r = `radius` (pixels, default 1).
/// Sampled exactly by inverting the triangle's CDF per axis: weight 1.
class TentFilter final : public Filter {
public:
    explicit TentFilter(double radius = 1.0);
    Vec2 radius() const override { return {m_radius, m_radius}; }
    double eval(const Vec2& offset) const override;
    FilterSample sample(const Vec2& u) const override;
    double pdf(const Vec2& offset) const override { return eval(offset); }
    std::string name() const override { return "tent"; }

private:
    double eval_1d(double x) const;
    double sample_1d(double u) const;
    double m_radius, m_inv_radius;
};

/// Mitsuba 3's `gaussian`: a Gaussian of standard deviation sigma = `stddev` (pixels, default
/// 0.5) cut off at r = 4 sigma and lowered by its value there so it reaches zero continuously:
///   f1(x) = max(0, exp(-x^2 / (2 sigma^2)) - exp(-(4 sigma)^2 / (2 sigma^2))) / Z,  |x| <= r,
/// Z its integral over [-r, r]. Sampled exactly per axis by inverting the closed-form CDF
/// (erf) with safeguarded Newton steps, started from a table: pdf == eval and weight 1.
class GaussianFilter final : public Filter {
public:
    explicit GaussianFilter(double stddev = 0.5);
    Vec2 radius() const override { return {m_radius, m_radius}; }
    double eval(const Vec2& offset) const override;
    /// Inversion of the CDF per axis, exact to rounding: cubic Hermite interpolation between 1024
    /// exact quantiles and their slopes; the sparse far tail is solved by bracketed Newton. A
    /// Newton loop per sample cost a quarter of `path`'s time, one Newton step (exp and erf) 6 %.
    FilterSample sample(const Vec2& u) const override;
    double pdf(const Vec2& offset) const override { return eval(offset); }
    std::string name() const override { return "gaussian"; }
    double stddev() const { return m_stddev; }

private:
    static constexpr int kTableSize = 64;
    static constexpr int kQuantiles = 1024;
    /// Unnormalised window exp(-x^2 / (2 sigma^2)) - bias on [-r, r], 0 outside.
    double window(double x) const;
    /// Integral of window() over [0, t], 0 <= t <= r.
    double half_cdf(double t) const;
    /// Exact inversion of the half CDF (Newton on erf, bracketed by m_table).
    double invert_half_cdf(double target) const;
    double sample_1d(double u) const;
    double m_stddev, m_radius, m_alpha, m_bias, m_inv_norm;  // m_inv_norm = 1 / Z
    std::array<double, kTableSize + 1> m_table;              // half_cdf at t = r k / kTableSize
    std::array<double, kQuantiles + 1> m_quantile;           // t with half_cdf(t) = half_cdf(r) k / kQuantiles
    std::array<double, kQuantiles + 1> m_slope;              // dt/dq at the quantiles (q = k)
};

/// The one-pixel box, shared (the default of a FilmSpec without a filter).
std::shared_ptr<const Filter> box_filter();

/// Visits every pixel (px, py) whose filter support contains the continuous raster position
/// `raster` (pixel (px, py) covers [px, px + 1) x [py, py + 1), its centre is + 0.5) and whose
/// weight f(raster - centre) is positive, calling f(px, py, weight). No bounds check: pixels
/// may lie outside the film (use the overload with a size to clip). Averaged over positions
/// the weights sum to 1 (the filter is normalised); pointwise the sum is exactly 1 for the box
/// and the tent with integer radius, and ripples slightly for the gaussian (about +-3% at
/// stddev 0.5, Poisson summation), which is no bias: each pixel's splat estimate is its own
/// filter-weighted integral.
template <class F>
void for_each_pixel_in_support(const Filter& filter, const Vec2& raster, F&& f) {
    const Vec2 r = filter.radius();
    // offset d = raster - (p + 0.5) lies in [-r, r) <=> p in (raster - r - 0.5, raster + r - 0.5].
    const int x0 = int(std::floor(raster.x - r.x - 0.5)) + 1, x1 = int(std::floor(raster.x + r.x - 0.5));
    const int y0 = int(std::floor(raster.y - r.y - 0.5)) + 1, y1 = int(std::floor(raster.y + r.y - 0.5));
    for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px) {
            const double w = filter.eval(Vec2(raster.x - (px + 0.5), raster.y - (py + 0.5)));
            if (w > 0) f(px, py, w);
        }
}

/// As above, restricted to the pixels of a width x height film.
template <class F>
void for_each_pixel_in_support(const Filter& filter, const Vec2& raster, int width, int height, F&& f) {
    for_each_pixel_in_support(filter, raster, [&](int px, int py, double w) {
        if (px >= 0 && py >= 0 && px < width && py < height) f(px, py, w);
    });
}

}  // namespace snell
