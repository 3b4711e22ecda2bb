#pragma once
#include <memory>

#include "core/sampler.h"

namespace snell {

/// Mitsuba's `ldsampler` (Mitsuba 0.6's default): every dimension pair draws from the same
/// (0,2)-sequence in base 2 (van der Corput x Sobol's second dimension), randomised per pixel,
/// dimension and block by random digit scrambling (xor with a random 32-bit word) and a shuffle of
/// the sample order (Kollig & Keller 2002, "Efficient Multidimensional Sampling"). next_1d() uses
/// the scrambled van der Corput sequence.
///  * The sample count is rounded up to a power of four, at least 4, as Mitsuba 3 does
///    (e.g. 16 -> 16, 20 -> 64); `sample_count()` reports the rounded value.
///  * The shuffle is an Owen scramble of the index's digits (not an arbitrary permutation, unlike
///    Mitsuba), so every power-of-two prefix 0..2^m-1 of a pixel's samples is still a
///    (0,m,2)-net: progressive renders stay stratified whenever they stop at a power of two.
///  * A "dimension" is one next_1d or next_2d call, with no limit on their number.
///  * Sample indices past sample_count (equal-time renders) form further blocks of sample_count:
///    block b = index / sample_count is a fresh, independently scrambled net.
class LowDiscrepancySampler final : public Sampler {
public:
    LowDiscrepancySampler(int sample_count, uint64_t seed);
    /// The sample count this sampler uses for `requested` (the next power of four, >= 4).
    static int round_sample_count(int requested);

    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    Vec2 next_2d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<LowDiscrepancySampler>(*this); }

    int sample_count() const { return int(m_count); }

private:
    uint64_t next_dimension_hash();

    uint32_t m_count;
    int m_log2_count;
    uint64_t m_seed;
    uint64_t m_pixel = 0, m_block = 0;  ///< pixel hash; index / sample_count
    uint32_t m_local = 0, m_dim = 0;    ///< index % sample_count; dimensions drawn so far
};

}  // namespace snell
