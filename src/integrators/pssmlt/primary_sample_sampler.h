#pragma once
// Kelemen et al. 2002, "A Simple and Robust Mutation Strategy for the Metropolis Light
// Transport Algorithm": a path is a point of the unit hypercube of primary samples (the
// uniform numbers an ordinary estimator would consume), and Metropolis mutates that point.
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sampler.h"

namespace snell {

/// A Sampler whose numbers are the current state of a primary-sample-space Markov chain.
/// Dimensions are created and mutated lazily on first use in an iteration, so an estimator
/// that consumes a variable number of numbers (Russian roulette, MNEE walks) works unchanged:
/// a dimension not used for k iterations receives the k small steps it missed, or a fresh
/// uniform value if a large step was accepted since (equivalent to mutating every dimension
/// every iteration, which keeps the proposal symmetric).
class PrimarySampleSampler final : public Sampler {
public:
    /// `stream` selects the PCG32 stream of fresh values and mutations; `large_step_probability`
    /// is Kelemen's p_large; a small step perturbs by s2 exp(-log(s2/s1) u) (random sign,
    /// wrapped to [0,1)), so steps lie in [s1, s2].
    PrimarySampleSampler(uint64_t seed, uint64_t stream, double large_step_probability, double s1 = 1.0 / 1024,
                         double s2 = 1.0 / 64);

    /// Restarts the dimension counter (the pixel and index are ignored: in primary sample
    /// space the film position is itself a sampled dimension).
    void start_pixel_sample(int px, int py, uint64_t index) override;
    double next_1d() override;
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<PrimarySampleSampler>(*this); }

    /// Begins proposing a mutation of the current state (a large step with probability
    /// p_large) and restarts the dimension counter.
    void start_iteration();
    /// Keeps the proposal as the new state.
    void accept();
    /// Restores the state from before the last start_iteration().
    void reject();
    /// True when the current proposal is a large step (fresh uniform numbers everywhere).
    bool large_step() const { return m_large_step; }
    /// Switches the stream of future fresh values and mutations, keeping the state: chains
    /// started from the same bootstrap path then diverge.
    void reseed(uint64_t seed, uint64_t stream) { m_rng.seed(seed, stream); }
    /// Uniform number from the chain's own stream (acceptance tests), not a state dimension.
    double uniform() { return m_rng.next_double(); }
    /// Makes `values` the current, accepted state (dimension i holds values[i]), as if the
    /// chain had arrived there: ERPT starts its chains at a path that an ordinary sampler
    /// produced. Dimensions beyond `values` are drawn fresh on first use, as unused dimensions
    /// of any state are independent uniform numbers.
    void set_state(const std::vector<double>& values);

private:
    struct Dim {
        double value = 0, backup = 0;
        int64_t modified = -1, modified_backup = -1;  ///< iteration of the last change
    };
    /// Brings dimension i up to the current iteration (fresh value or missed small steps).
    void update(size_t i);
    double small_step(double x);

    PCG32 m_rng;
    double m_p_large, m_s1, m_s2;
    std::vector<Dim> m_dims;
    size_t m_next = 0;  ///< next dimension to hand out in this iteration
    int64_t m_iteration = 0;
    int64_t m_last_large_step = 0;  ///< iteration of the last accepted large step
    bool m_large_step = true;       ///< iteration 0 draws every value fresh
};

}  // namespace snell
