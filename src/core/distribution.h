#pragma once
#include <algorithm>
#include <vector>

#include "core/vector.h"

namespace snell {

/// Piecewise-constant 1D distribution over n bins (discrete pmf and continuous pdf on [0,1)).
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::vector<double> f) : m_f(std::move(f)), m_cdf(m_f.size() + 1, 0.0) {
        const size_t n = m_f.size();
        for (size_t i = 0; i < n; ++i) m_cdf[i + 1] = m_cdf[i] + std::max(0.0, m_f[i]);
        m_sum = m_cdf[n];
        if (m_sum > 0) {
            for (size_t i = 1; i <= n; ++i) m_cdf[i] /= m_sum;
        } else {
            for (size_t i = 1; i <= n; ++i) m_cdf[i] = double(i) / double(n);
        }
        if (n) m_cdf[n] = 1.0;
    }
    size_t size() const { return m_f.size(); }
    double sum() const { return m_sum; }
    /// Discrete probability of bin i.
    double pmf(size_t i) const { return m_cdf[i + 1] - m_cdf[i]; }
    /// Samples a bin; `u_remapped` (optional) receives u rescaled to [0,1) within the bin.
    size_t sample_discrete(double u, double* pmf_out = nullptr, double* u_remapped = nullptr) const {
        const size_t n = m_f.size();
        size_t i = size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin());
        i = std::min(n - 1, i == 0 ? 0 : i - 1);
        // Skip zero-probability bins that upper_bound may land on at ties.
        while (i + 1 < n && pmf(i) == 0) ++i;
        const double p = pmf(i);
        if (pmf_out) *pmf_out = p;
        if (u_remapped) *u_remapped = p > 0 ? std::min((u - m_cdf[i]) / p, 0x1.fffffffffffffp-1) : 0.0;
        return i;
    }
    /// Samples x in [0,1) with density pdf(x) = n * pmf(bin(x)).
    double sample_continuous(double u, double* pdf_out, size_t* bin = nullptr) const {
        double p, du;
        const size_t i = sample_discrete(u, &p, &du);
        if (pdf_out) *pdf_out = p * double(m_f.size());
        if (bin) *bin = i;
        return (double(i) + du) / double(m_f.size());
    }
    double pdf_continuous(double x) const {
        const size_t n = m_f.size();
        const size_t i = std::min(n - 1, size_t(std::max(0.0, x) * double(n)));
        return pmf(i) * double(n);
    }

private:
    std::vector<double> m_f, m_cdf;
    double m_sum = 0;
};

}  // namespace snell
