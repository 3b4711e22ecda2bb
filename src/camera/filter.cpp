#include "camera/filter.h"

#include <algorithm>
#include <cassert>

namespace snell {

namespace {

/// Largest double below 1: keeps u - 0.5 inside the half-open box and the tent's branches apart.
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;

double clamp_unit(double u) { return std::min(std::max(u, 0.0), kOneMinusEpsilon); }

}  // namespace

// --- box ---------------------------------------------------------------------------------

double BoxFilter::eval(const Vec2& o) const {
    return (o.x >= -0.5 && o.x < 0.5 && o.y >= -0.5 && o.y < 0.5) ? 1.0 : 0.0;
}

FilterSample BoxFilter::sample(const Vec2& u) const {
    return {Vec2(clamp_unit(u.x) - 0.5, clamp_unit(u.y) - 0.5), 1.0};
}

// --- tent --------------------------------------------------------------------------------

TentFilter::TentFilter(double radius) : m_radius(radius), m_inv_radius(1.0 / radius) { assert(radius > 0); }

double TentFilter::eval_1d(double x) const {
    const double a = std::abs(x);
    return a < m_radius ? (1 - a * m_inv_radius) * m_inv_radius : 0.0;
}

double TentFilter::eval(const Vec2& o) const { return eval_1d(o.x) * eval_1d(o.y); }

double TentFilter::sample_1d(double u) const {
    // Inverse CDF of the triangle on [-r, r]: each half holds probability 1/2.
    u = clamp_unit(u);
    return u < 0.5 ? m_radius * (std::sqrt(2 * u) - 1) : m_radius * (1 - std::sqrt(2 - 2 * u));
}

FilterSample TentFilter::sample(const Vec2& u) const { return {Vec2(sample_1d(u.x), sample_1d(u.y)), 1.0}; }

// --- gaussian ----------------------------------------------------------------------------

GaussianFilter::GaussianFilter(double stddev) : m_stddev(stddev) {
    assert(stddev > 0);
    m_radius = 4 * stddev;  // Mitsuba cuts off after 4 standard deviations
    m_alpha = 1.0 / (2 * stddev * stddev);
    m_bias = std::exp(-m_alpha * m_radius * m_radius);  // exp(-8): the window's value at the cut-off
    m_inv_norm = 1.0 / (2 * half_cdf(m_radius));
    for (int k = 0; k <= kTableSize; ++k) m_table[size_t(k)] = half_cdf(m_radius * k / kTableSize);
    for (int k = 0; k <= kQuantiles; ++k) m_quantile[size_t(k)] = invert_half_cdf(m_table[kTableSize] * k / kQuantiles);
    m_quantile[kQuantiles] = m_radius;
    // dt/dq at each knot (the inverse of the density): the CDF's step per quantile over the window.
    for (int k = 0; k <= kQuantiles; ++k) {
        const double g = window(m_quantile[size_t(k)]);
        m_slope[size_t(k)] = g > 0 ? m_table[kTableSize] / kQuantiles / g : kInfinity;
    }
}

double GaussianFilter::window(double x) const {
    return std::abs(x) <= m_radius ? std::max(0.0, std::exp(-m_alpha * x * x) - m_bias) : 0.0;
}

double GaussianFilter::half_cdf(double t) const {
    // integral_0^t exp(-x^2 / (2 sigma^2)) dx = sigma sqrt(pi / 2) erf(t / (sigma sqrt 2)).
    return m_stddev * std::sqrt(kPi / 2) * std::erf(t / (m_stddev * std::sqrt(2.0))) - m_bias * t;
}

double GaussianFilter::eval(const Vec2& o) const { return window(o.x) * window(o.y) * m_inv_norm * m_inv_norm; }

double GaussianFilter::invert_half_cdf(double target) const {
    // Bracket from the table, initial guess by linear interpolation inside it.
    int k = int(std::upper_bound(m_table.begin(), m_table.end(), target) - m_table.begin()) - 1;
    k = std::clamp(k, 0, kTableSize - 1);
    const double step = m_radius / kTableSize;
    double lo = step * k, hi = step * (k + 1);
    const double span = m_table[size_t(k) + 1] - m_table[size_t(k)];
    double t = span > 0 ? lo + step * (target - m_table[size_t(k)]) / span : lo;
    // Newton on the CDF (its derivative is the window, positive inside), kept in the bracket
    // by bisection; converges to rounding error in a few steps.
    for (int i = 0; i < 64; ++i) {
        const double d = half_cdf(t) - target;
        if (d == 0) break;
        (d > 0 ? hi : lo) = t;
        const double g = window(t);
        double next = g > 0 ? t - d / g : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const bool done = std::abs(next - t) <= 1e-15 * m_radius || hi - lo <= 1e-15 * m_radius;
        t = next;
        if (done) break;
    }
    return std::clamp(t, 0.0, m_radius);
}

double GaussianFilter::sample_1d(double u) const {
    // The window is even: pick the side from u's half, then solve half_cdf(t) = |s| half_cdf(r).
    const double s = 2 * clamp_unit(u) - 1;
    const double q = std::abs(s) * kQuantiles;
    const int k = std::min(kQuantiles - 1, int(q));
    const double t0 = m_quantile[size_t(k)], t1 = m_quantile[size_t(k) + 1];
    const double target = std::abs(s) * m_table[kTableSize];
    double t;
    if (t1 - t0 > 8 * m_radius / kQuantiles || !(m_slope[size_t(k) + 1] < kInfinity)) {
        t = invert_half_cdf(target);  // the far tail, where quantiles are sparse: the full solve
    } else {
        // Cubic Hermite interpolation of the quantile function from the knots' values and
        // slopes: CDF error below 1e-10 (filter test SamplingInvertsTheCdf asks 1e-9), with
        // no exp() or erf() on the path of every camera sample.
        const double f = q - k, f2 = f * f, f3 = f2 * f;
        t = (2 * f3 - 3 * f2 + 1) * t0 + (f3 - 2 * f2 + f) * m_slope[size_t(k)] + (-2 * f3 + 3 * f2) * t1 +
            (f3 - f2) * m_slope[size_t(k) + 1];
        if (t1 - t0 > 2 * m_radius / kQuantiles) {  // the tail, where the quantiles spread out:
            const double g = window(t);             // one Newton step squares the error there
            if (g > 0) t -= (half_cdf(t) - target) / g;
        }
        t = std::clamp(t, t0, t1);
    }
    return s < 0 ? -t : t;
}

FilterSample GaussianFilter::sample(const Vec2& u) const {
    // Exact inversion: the density of the offsets is eval itself, so f / pdf = 1.
    return {Vec2(sample_1d(u.x), sample_1d(u.y)), 1.0};
}

std::shared_ptr<const Filter> box_filter() {
    static const std::shared_ptr<const Filter> box = std::make_shared<BoxFilter>();
    return box;
}

}  // namespace snell
