#pragma once
#include <memory>

#include "core/sampler.h"

namespace snell {

/// Mitsuba's `orthogonal` sampler: orthogonal-array sampling (Jarosz, Enayet, Kensler, Kilpatrick
/// and Christensen 2019, "Orthogonal Array Sampling for Monte Carlo Rendering") of strength 2,
/// from Bose's construction. sample_count = p^2 for a prime p (a request is rounded up to the next
/// such square). Sample i = (a, b) in base p takes the value A_j(i) in column j of p + 1 columns:
/// a, b, and (a + (j - 1) b) mod p; any two columns hold every pair of values exactly once, so
/// *every* 2D projection of the first p + 1 dimensions is stratified p x p, not only the pairs of
/// one next_2d call (as with multijitter). Inside its stratum, a point's sub-stratum comes from the
/// next column, which runs over all p values among the stratum's points, so each dimension is also
/// stratified into p^2 intervals (multi-jittering). Values, sub-strata and point order are permuted
/// by hashes of (seed, pixel, dimension round, block); dimensions past p + 1 start a new,
/// independently randomised round of columns; indices past sample_count form new blocks.
class OrthogonalSampler final : public Sampler {
public:
    OrthogonalSampler(int sample_count, uint64_t seed, bool jitter = true);
    /// The prime p with p^2 >= requested, smallest.
    static int prime_for(int requested);
    static int round_sample_count(int requested) { return prime_for(requested) * prime_for(requested); }

    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    Vec2 next_2d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<OrthogonalSampler>(*this); }

    int sample_count() const { return int(m_p * m_p); }

private:
    /// The OA value of the current point in column j (0 <= j <= p) of the current round.
    uint32_t column(uint32_t j) const;
    /// The coordinate of the current point in column j of the current round.
    double coordinate(uint32_t j) const;
    /// The next column to use, opening a new round when `need` columns no longer fit.
    uint32_t take_columns(uint32_t need);

    uint32_t m_p = 2;
    uint64_t m_seed;
    bool m_jitter;
    uint64_t m_pixel = 0, m_block = 0;
    uint32_t m_a = 0, m_b = 0;        ///< the current point's base-p digits (after shuffling)
    uint32_t m_local = 0;             ///< index % sample_count
    uint32_t m_round = 0, m_col = 0;  ///< dimension round, next column in it
    uint64_t m_round_hash = 0;
};

}  // namespace snell
