#pragma once
#include <memory>

#include "core/rng.h"
#include "core/sampler.h"

namespace snell {

/// Mitsuba's `independent` sampler: fresh uniform numbers for every dimension. It stratifies
/// nothing, so it accepts any sample index and any number of dimensions.
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
