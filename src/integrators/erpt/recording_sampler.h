#pragma once
// A sampler that passes another sampler's numbers through and writes each one down. ERPT
// evaluates its seed path with the pixel sample's own sampler through this wrapper; the
// recorded numbers are the seed's primary sample (Kelemen et al. 2002), at which its Metropolis
// chains then start.
#include <stdexcept>
#include <vector>

#include "core/sampler.h"

namespace snell {

/// Forwards next_1d/next_2d to `base` and appends every number handed out to `record`, in the
/// order a PrimarySampleSampler hands out its dimensions (a 2D sample is x, then y).
class RecordingSampler final : public Sampler {
public:
    RecordingSampler(Sampler& base, std::vector<double>& record) : m_base(base), m_record(record) {}

    /// A recording belongs to one evaluation inside one pixel sample: moving it is a bug.
    void start_pixel_sample(int, int, uint64_t) override {
        throw std::logic_error("RecordingSampler: start_pixel_sample inside a recorded evaluation");
    }
    double next_1d() override {
        const double u = m_base.next_1d();
        m_record.push_back(u);
        return u;
    }
    /// The base's own 2D sample (a stratified base keeps its strata), recorded as two numbers.
    Vec2 next_2d() override {
        const Vec2 u = m_base.next_2d();
        m_record.push_back(u.x);
        m_record.push_back(u.y);
        return u;
    }
    std::unique_ptr<Sampler> clone() const override {
        throw std::logic_error("RecordingSampler: cannot be cloned (it writes into one record)");
    }

private:
    Sampler& m_base;
    std::vector<double>& m_record;
};

}  // namespace snell
