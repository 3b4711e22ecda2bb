#pragma once
#include <memory>

#include "core/sampler.h"

namespace snell {

/// Mitsuba's `multijitter` sampler: correlated multi-jittered sampling (Kensler 2013, "Correlated
/// Multi-Jittered Sampling"). next_2d() places sample_count = cols x rows points, one in every cell
/// of a cols x rows grid *and* one in every one of the sample_count 1D strata of x and of y;
/// the sub-stratum shuffles of all columns share one permutation (and of all rows another),
/// Kensler's "correlated" variant, which reduces clumping. next_1d() is 1D stratified.
///  * The grid: rows = the largest divisor of sample_count with rows^2 <= sample_count and
///    2 rows^2 >= sample_count (e.g. 32 = 8 x 4, 64 = 8 x 8); when there is none, Mitsuba's rule:
///    rows = floor(sqrt(n)), cols = ceil(n / rows), rounding the count up (e.g. 7 -> 4 x 2 = 8,
///    10 -> 4 x 3 = 12). `sample_count()` reports the rounded value.
///  * Order of the points, grid permutations and jitter are hashes of (seed, pixel, dimension,
///    block); a "dimension" is one next_1d or next_2d call, with no limit on their number.
///  * Sample indices past sample_count (equal-time renders) form further blocks of sample_count:
///    block b = index / sample_count is a fresh, independently randomised pattern.
///  * jitter = false puts every point at its sub-stratum's centre (Mitsuba's `jitter` parameter).
class MultiJitterSampler final : public Sampler {
public:
    MultiJitterSampler(int sample_count, uint64_t seed, bool jitter = true);
    /// The (cols, rows) grid used for `requested` samples; sample_count = cols * rows.
    static void grid_for(int requested, int& cols, int& rows);
    static int round_sample_count(int requested);

    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    Vec2 next_2d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<MultiJitterSampler>(*this); }

    int sample_count() const { return int(m_count); }
    int columns() const { return int(m_cols); }
    int rows() const { return int(m_rows); }

private:
    uint64_t next_dimension_hash();

    uint32_t m_cols = 1, m_rows = 1, m_count = 1;
    uint64_t m_seed;
    bool m_jitter;
    uint64_t m_pixel = 0, m_block = 0;  ///< pixel hash; index / sample_count
    uint32_t m_local = 0, m_dim = 0;    ///< index % sample_count; dimensions drawn so far
};

}  // namespace snell
