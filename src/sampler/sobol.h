#pragma once
#include <memory>

#include "core/sampler.h"

namespace snell {

/// snell's default for its own scenes: a scrambled Sobol (0,2)-sequence per dimension pair
/// ("padded" Sobol, like pbrt-v4's PaddedSobolSampler), randomised per pixel with hash-based Owen
/// scrambling (Burley 2020, "Practical Hash-based Owen Scrambling").
///  * next_2d(): the first two Sobol dimensions (van der Corput, Pascal matrix) at a shuffled
///    index, each coordinate Owen-scrambled with its own hash of (seed, pixel, dimension).
///    next_1d(): the Owen-scrambled van der Corput sequence at a shuffled index.
///  * Decorrelation of dimensions: each dimension shuffles the sample index with its own
///    hash-based Owen scramble of the index digits (Burley 2020, Sec. 4); a pair without the
///    shuffle would repeat the same points in the same order as every other pair.
///  * Progressive: the shuffle maps every aligned block of 2^m indices onto an aligned block of
///    2^m Sobol indices, so every power-of-two prefix of a pixel's samples is a (0,m,2)-net in
///    every dimension pair, whatever sample_count says.
///  * Any index: past sample_count (equal-time renders) the sequence just continues; the 32-bit
///    Sobol index covers 2^32 samples per pixel, and each further block of 2^32 is scrambled anew.
///  * A "dimension" is one next_1d or next_2d call, with no limit on their number (every
///    dimension is padded with its own scramble, so none falls back to independent numbers).
///  * sample_count is not used to build points (any count works; powers of two stratify best);
///    it is kept for `sample_count()`.
class SobolSampler final : public Sampler {
public:
    SobolSampler(int sample_count, uint64_t seed);

    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    Vec2 next_2d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(*this); }

    int sample_count() const { return m_count; }

private:
    uint64_t next_dimension_hash();
    uint32_t shuffled_index(uint64_t h) const;

    int m_count;
    uint64_t m_seed;
    uint64_t m_pixel = 0;             ///< hash of (seed, pixel, index / 2^32)
    uint32_t m_index = 0, m_dim = 0;  ///< index modulo 2^32; dimensions drawn so far
    uint32_t m_index_reversed = 0;    ///< reverse_bits(m_index)
};

}  // namespace snell
