#pragma once
#include <memory>

#include "core/sampler.h"

namespace snell {

/// Mitsuba's `stratified` sampler: every dimension is stratified on its own (padding, Kollig &
/// Keller 2002) and jittered within its stratum.
///  * The sample count is rounded up to the next perfect square res^2, as Mitsuba 3 does
///    (e.g. 20 -> 25); `sample_count()` reports the rounded value.
///  * next_1d(): sample_count strata of width 1/sample_count.
///  * next_2d(): a res x res grid, one point per cell.
///  * The strata of each dimension are visited in a pseudo-random order that depends on (seed,
///    pixel, dimension, block), like pbrt-v4's StratifiedSampler, so dimensions are decorrelated.
///  * A "dimension" is one next_1d or next_2d call; there is no limit on their number.
///  * Sample indices past sample_count (equal-time renders) form further blocks of sample_count:
///    block b = index / sample_count is a fresh, independently randomised stratified set.
///  * jitter = false puts every point at its stratum's centre (Mitsuba's `jitter` parameter).
class StratifiedSampler final : public Sampler {
public:
    StratifiedSampler(int sample_count, uint64_t seed, bool jitter = true);
    /// The sample count this sampler stratifies for `requested` (the next perfect square).
    static int round_sample_count(int requested);

    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    Vec2 next_2d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<StratifiedSampler>(*this); }

    int sample_count() const { return int(m_count); }
    int resolution() const { return int(m_res); }

private:
    /// Hash of (pixel, block, dimension) for the next dimension; advances the dimension.
    uint64_t next_dimension_hash() { return hash_dim(m_dim++); }
    uint64_t hash_dim(uint32_t dim) const;

    uint32_t m_count, m_res;
    uint64_t m_seed;
    bool m_jitter;
    uint64_t m_pixel = 0, m_block = 0;  ///< pixel hash; index / sample_count
    uint32_t m_local = 0, m_dim = 0;    ///< index % sample_count; dimensions drawn so far
};

}  // namespace snell
