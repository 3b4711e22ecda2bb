#pragma once
// solutions=fallback: the paper's estimator wherever the straight segment x_b -> x_c is clear
// of opaque surfaces, and the unbiased estimator's surface solutions where an opaque surface
// blocks it (an object inside glass). MIS by Alg. 2 in the first case, by the solution density
// in the second: unbiased.
#include "manifold/estimator_base.h"

namespace snell {

class FallbackEstimator : public EstimatorBase {
public:
    using EstimatorBase::EstimatorBase;
    void solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
               const LightPoint& lp, const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k,
               SolutionSet& out) const;
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                   const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda) const;
};

}  // namespace snell
