#pragma once
// solutions=unbiased (the default): the straight seed's solution plus every distinct solution a
// first round of surface trials finds, each weighted by the rounds of further trials until one
// finds it again, an unbiased estimate of 1 / p (Specular Manifold Sampling's, with M = 1).
#include "manifold/multi_solution_estimator.h"

namespace snell {

class UnbiasedEstimator final : public MultiSolutionEstimator {
public:
    using MultiSolutionEstimator::MultiSolutionEstimator;

protected:
    void trials_on(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                   const LightPoint& lp, const CasterChoice& casters, PCG32& rng, HalfVectorDraws& draws, int max_k,
                   const Foreign& foreign, size_t before, SolutionSet& out) const override {
        count_trials_to_refind(q, ctx, slot, light, pmf, lp, casters, rng, draws, max_k, foreign, before, out);
    }
};

}  // namespace snell
