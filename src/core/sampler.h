#pragma once
#include <memory>

#include "core/rng.h"
#include "core/vector.h"

namespace snell {

/// All randomness of an estimator goes through this interface (STYLE.md habit 6), so a
/// primary-sample-space Metropolis sampler can later replace the independent one. The pixel
/// samplers (independent, stratified, multijitter, ldsampler, sobol) live in src/sampler/.
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

}  // namespace snell
