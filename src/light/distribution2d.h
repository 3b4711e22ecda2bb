#pragma once
// Piecewise-constant density on the unit square, used to importance sample environment maps.
#include <vector>

#include "core/distribution.h"
#include "core/vector.h"

namespace snell {

/// Piecewise-constant 2D distribution over [0,1)^2 made of nu x nv equal bins (pbrt's
/// marginal/conditional construction): v is drawn from the marginal over rows, then u from
/// that row's conditional. Densities are with respect to area on the unit square (du dv).
class Distribution2D {
public:
    Distribution2D() = default;
    /// `f` holds nu * nv non-negative bin values, row-major: f[iv * nu + iu].
    Distribution2D(const std::vector<double>& f, size_t nu, size_t nv) : m_nu(nu), m_nv(nv) {
        std::vector<double> row_sums(nv, 0.0);
        m_cond.reserve(nv);
        for (size_t iv = 0; iv < nv; ++iv) {
            std::vector<double> row(f.begin() + long(iv * nu), f.begin() + long((iv + 1) * nu));
            for (double x : row) row_sums[iv] += std::max(0.0, x);
            m_cond.emplace_back(std::move(row));
        }
        m_marginal = Distribution1D(std::move(row_sums));
    }

    size_t nu() const { return m_nu; }
    size_t nv() const { return m_nv; }
    /// Sum of all bin values (0 for an all-zero input, which then samples uniformly).
    double sum() const { return m_marginal.sum(); }

    /// Maps a uniform point u to (u, v) in [0,1)^2; `pdf` receives the density in du dv.
    Vec2 sample(const Vec2& u, double* pdf) const {
        double pdf_v, pdf_u;
        size_t iv;
        const double v = m_marginal.sample_continuous(u.y, &pdf_v, &iv);
        const double uu = m_cond[iv].sample_continuous(u.x, &pdf_u);
        if (pdf) *pdf = pdf_u * pdf_v;
        return {uu, v};
    }

    /// Density in du dv of sample() returning `uv` (clamped into the square).
    double pdf(const Vec2& uv) const {
        const size_t iv = std::min(m_nv - 1, size_t(std::max(0.0, uv.y) * double(m_nv)));
        return m_marginal.pdf_continuous(uv.y) * m_cond[iv].pdf_continuous(uv.x);
    }

private:
    size_t m_nu = 0, m_nv = 0;
    std::vector<Distribution1D> m_cond;  // one per row (v bin), over u
    Distribution1D m_marginal;           // over rows
};

}  // namespace snell
