#pragma once
// solutions=all: every distinct admissible path that the straight seed and `trials` surface
// seeds walk to, each counted once. Consistent; biased low for finite trials by the
// solutions no seed found.
#include "manifold/multi_solution_estimator.h"

namespace snell {

class AllSolutionsEstimator final : public MultiSolutionEstimator {
public:
    using MultiSolutionEstimator::MultiSolutionEstimator;

protected:
    void trials_on(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                   const LightPoint& lp, const CasterChoice& casters, PCG32& rng, HalfVectorDraws& draws, int max_k,
                   const Foreign& foreign, size_t before, SolutionSet& out) const override {
        walk_every_trial(q, ctx, slot, light, pmf, lp, casters, rng, draws, max_k, foreign, before, out);
    }
};

}  // namespace snell
