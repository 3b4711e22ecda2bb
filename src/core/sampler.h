#pragma once
#include <memory>

#include "core/rng.h"
#include "core/vector.h"

namespace snell {

/// All randomness of an estimator goes through this interface (STYLE.md habit 6), so a
/// primary-sample-space Metropolis sampler can later replace the independent one.
class Sampler {
public:
    virtual ~Sampler() = default;
    /// Positions the sampler on sample `index` of pixel (px, py); the stream is a pure
    /// function of (seed, pixel, index), which makes renders independent of thread count.
    virtual void start_pixel_sample(int px, int py, uint64_t index) = 0;
    virtual double next_1d() = 0;
    virtual Vec2 next_2d() {
        const double a = next_1d();
        return {a, next_1d()};
    }
    virtual std::unique_ptr<Sampler> clone() const = 0;
};

/// Mitsuba's `independent` sampler: fresh uniform numbers for every dimension.
class IndependentSampler final : public Sampler {
public:
    explicit IndependentSampler(uint64_t seed = 0) : m_seed(seed) {}
    void start_pixel_sample(int px, int py, uint64_t index) override {
        const uint64_t pixel = (uint64_t(uint32_t(py)) << 32) | uint32_t(px);
        m_rng.seed(mix_bits(pixel ^ mix_bits(m_seed)), mix_bits(index + 0x9e3779b97f4a7c15ULL * (m_seed + 1)));
    }
    double next_1d() override { return m_rng.next_double(); }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(*this); }
    uint64_t seed() const { return m_seed; }

private:
    uint64_t m_seed;
    PCG32 m_rng;
};

}  // namespace snell
