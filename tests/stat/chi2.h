#pragma once
// Chi-square goodness-of-fit test of a direction sampler against its claimed density, in the
// style of Mitsuba's ChiSquareTest and pbrt's BSDF tests:
//   1. the sphere is cut into theta_res x phi_res bins of equal solid angle (uniform in
//      cos(theta) and phi), so dOmega = dz dphi and no Jacobian enters the integrals;
//   2. the claimed pdf (solid angle) is integrated over each bin by nested adaptive Simpson
//      quadrature (started on a sub-grid so narrow lobes are not missed);
//   3. `samples` directions are drawn and histogrammed; failed samples (nullopt) go into an
//      extra "no sample" cell whose expectation is N (1 - integral of the pdf), which also
//      checks the pdf's normalisation against the sampler's success rate;
//   4. cells with expected count < min_expected are pooled; Pearson's statistic is compared
//      with the chi-square distribution (upper regularised incomplete gamma, implemented
//      here) and rejected below significance corrected for `test_count` tests (Sidak).
// Reusable for any sampler of directions: BSDFs, phase functions, lights, warps.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/vector.h"

namespace snell::test {

/// Upper regularised incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), a > 0.
/// Series for x < a + 1, modified Lentz continued fraction otherwise (both converge fast).
inline double regularized_gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double log_prefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {
        // P(a, x) = x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)).
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::abs(term) < std::abs(sum) * 1e-16) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
    }
    // Continued fraction for Q: 1/(x+1-a- 1(1-a)/(x+3-a- 2(2-a)/(x+5-a- ...))).
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-16) break;
    }
    return std::exp(log_prefix) * h;
}

/// P(X >= chi2) for X chi-square distributed with `dof` degrees of freedom.
inline double chi2_p_value(double chi2, int dof) { return regularized_gamma_q(0.5 * dof, 0.5 * chi2); }

/// Pools the (expected, observed) cells whose expected count is below `min_expected` into one
/// cell (folded into the smallest regular cell if the pool is still too small), as Pearson's
/// test needs.
inline std::vector<std::pair<double, double>> pool_cells(std::vector<std::pair<double, double>> cells,
                                                         double min_expected) {
    std::sort(cells.begin(), cells.end());
    std::vector<std::pair<double, double>> pooled;
    double pe = 0, po = 0;
    for (auto& c : cells) {
        if (c.first < min_expected) {
            pe += c.first;
            po += c.second;
        } else {
            pooled.push_back(c);
        }
    }
    if (pe > 0 || po > 0) {
        if (pe >= min_expected || pooled.empty()) {
            pooled.push_back({pe, po});
        } else {  // still too small: fold into the smallest regular cell
            pooled.front().first += pe;
            pooled.front().second += po;
        }
    }
    return pooled;
}

/// Pearson's statistic over pooled (expected, observed) cells, its p-value, and the verdict at
/// family-wise level `significance` over `test_count` tests (Sidak); notes go to `msg`.
template <class Result>
void pearson_test(const std::vector<std::pair<double, double>>& pooled, double significance, int test_count,
                  Result& res, std::ostream& msg) {
    for (auto& [e, o] : pooled) {
        if (e <= 0) {
            if (o > 0) {
                msg << "observed " << o << " samples where the pdf integrates to zero; ";
                res.chi2 = kInfinity;
            }
            continue;
        }
        res.chi2 += sqr(o - e) / e;
    }
    res.dof = int(pooled.size()) - 1;
    res.p_value = std::isfinite(res.chi2) ? chi2_p_value(res.chi2, res.dof) : 0.0;
    res.threshold = 1 - std::pow(1 - significance, 1.0 / test_count);
    res.passed = res.p_value >= res.threshold;
}

/// Adaptive Simpson quadrature of f over [a, b] to absolute tolerance eps, after first
/// splitting into `panels` equal pieces (so features narrower than the interval are seen).
template <typename F>
double adaptive_simpson(const F& f, double a, double b, double eps, int panels = 8, int max_depth = 14) {
    struct Rec {
        const F& f;
        double run(double a, double fa, double m, double fm, double b, double fb, double whole, double eps,
                   int depth) const {
            const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
            const double flm = f(lm), frm = f(rm);
            const double left = (m - a) / 6 * (fa + 4 * flm + fm);
            const double right = (b - m) / 6 * (fm + 4 * frm + fb);
            const double diff = left + right - whole;
            if (depth <= 0 || std::abs(diff) <= 15 * eps) return left + right + diff / 15;
            return run(a, fa, lm, flm, m, fm, left, 0.5 * eps, depth - 1) +
                   run(m, fm, rm, frm, b, fb, right, 0.5 * eps, depth - 1);
        }
    } rec{f};
    double sum = 0;
    const double h = (b - a) / panels;
    double x0 = a, f0 = f(a);
    for (int i = 0; i < panels; ++i) {
        const double x1 = i + 1 == panels ? b : a + (i + 1) * h, xm = 0.5 * (x0 + x1);
        const double f1 = f(x1), fm = f(xm);
        const double whole = (x1 - x0) / 6 * (f0 + 4 * fm + f1);
        sum += rec.run(x0, f0, xm, fm, x1, f1, whole, eps / panels, max_depth);
        x0 = x1;
        f0 = f1;
    }
    return sum;
}

struct Chi2Options {
    int theta_res = 10;             ///< bins in cos(theta) over [-1, 1]
    int phi_res = 20;               ///< bins in phi over [0, 2 pi)
    size_t samples = 1000000;       ///< directions drawn
    double min_expected = 5.0;      ///< pool cells expecting fewer samples than this
    double significance = 0.01;     ///< per-family false-rejection rate
    int test_count = 1;             ///< number of chi-square tests in the family (Sidak correction)
    double integration_eps = 1e-8;  ///< absolute quadrature tolerance per bin (probability)
    uint64_t seed = 7;
};

struct Chi2Result {
    bool passed = false;
    double p_value = 0, chi2 = 0, threshold = 0;
    int dof = 0;
    double pdf_integral = 0;                 ///< integral of the pdf over the sphere
    size_t valid_samples = 0;                ///< samples that produced a direction
    std::vector<double> observed, expected;  ///< per bin, row-major (theta, phi)
    std::string message;
};

/// Runs the test. `sample(rng)` returns a unit direction or std::nullopt (no sample);
/// `pdf(w)` is the solid-angle density the sampler claims.
inline Chi2Result chi2_sphere_test(const std::function<std::optional<Vec3>(PCG32&)>& sample,
                                   const std::function<double(const Vec3&)>& pdf, const Chi2Options& opt = {}) {
    const int nt = opt.theta_res, np = opt.phi_res, nbins = nt * np;
    const double dz = 2.0 / nt, dphi = 2 * kPi / np;
    Chi2Result res;
    res.observed.assign(nbins, 0.0);
    res.expected.assign(nbins, 0.0);

    // Histogram the samples.
    PCG32 rng(opt.seed, 0x5eed);
    size_t failed = 0;
    for (size_t i = 0; i < opt.samples; ++i) {
        const auto w = sample(rng);
        if (!w) {
            ++failed;
            continue;
        }
        const double z = clamp(w->z, -1.0, 1.0);
        double phi = std::atan2(w->y, w->x);
        if (phi < 0) phi += 2 * kPi;
        const int it = std::min(nt - 1, std::max(0, int((z + 1) / dz)));
        const int ip = std::min(np - 1, std::max(0, int(phi / dphi)));
        res.observed[it * np + ip] += 1;
    }
    res.valid_samples = opt.samples - failed;

    // Integrate the pdf over each bin (dOmega = dz dphi).
    auto eval_pdf = [&](double z, double phi) {
        const double s = safe_sqrt(1 - z * z);
        const double p = pdf(Vec3(s * std::cos(phi), s * std::sin(phi), z));
        return std::isfinite(p) ? p : 0.0;
    };
    double total = 0;
    for (int it = 0; it < nt; ++it)
        for (int ip = 0; ip < np; ++ip) {
            const double z0 = -1 + it * dz, p0 = ip * dphi;
            const double eps_inner = opt.integration_eps / dz;
            auto inner = [&](double z) {
                return adaptive_simpson([&](double phi) { return eval_pdf(z, phi); }, p0, p0 + dphi, eps_inner);
            };
            const double v = adaptive_simpson(inner, z0, z0 + dz, opt.integration_eps);
            res.expected[it * np + ip] = v * double(opt.samples);
            total += v;
        }
    res.pdf_integral = total;

    // Cells: the bins plus "no sample"; pool the small ones.
    std::vector<std::pair<double, double>> cells;  // (expected, observed)
    for (int i = 0; i < nbins; ++i) cells.push_back({res.expected[i], res.observed[i]});
    cells.push_back({std::max(0.0, 1 - total) * double(opt.samples), double(failed)});
    const std::vector<std::pair<double, double>> pooled = pool_cells(std::move(cells), opt.min_expected);
    std::ostringstream msg;
    if (pooled.size() < 2) {
        res.message = "fewer than two cells after pooling";
        return res;
    }
    pearson_test(pooled, opt.significance, opt.test_count, res, msg);
    msg << "chi2 = " << res.chi2 << ", dof = " << res.dof << ", p = " << res.p_value << " (threshold " << res.threshold
        << "), pdf integral = " << total << ", valid samples = " << res.valid_samples << "/" << opt.samples;
    if (!res.passed) {
        // The worst bins, to see where sampler and pdf disagree.
        std::vector<int> idx(nbins);
        std::iota(idx.begin(), idx.end(), 0);
        auto dev = [&](int i) {
            const double e = res.expected[i], o = res.observed[i];
            return e > 0 ? sqr(o - e) / e : (o > 0 ? kInfinity : 0.0);
        };
        std::sort(idx.begin(), idx.end(), [&](int a, int b) { return dev(a) > dev(b); });
        msg << "\n  worst bins (theta, phi: observed / expected):";
        for (int k = 0; k < std::min(nbins, 6); ++k)
            msg << "\n    (" << idx[k] / np << ", " << idx[k] % np << "): " << res.observed[idx[k]] << " / "
                << res.expected[idx[k]];
        msg << "\n  no sample: " << failed << " / " << std::max(0.0, 1 - total) * opt.samples;
    }
    res.message = msg.str();
    return res;
}

}  // namespace snell::test
