#pragma once
// The paper's estimator (solutions=one): Alg. 1 from the straight seed x_b -> x_c alone, its
// density by Alg. 2 (0 for a path that seed does not walk to: caustic folds, Fig. 7).
#include "manifold/estimator_base.h"

namespace snell {

class StraightSeedEstimator : public EstimatorBase {
public:
    using EstimatorBase::EstimatorBase;
    /// Alg. 1 lines 3-5 for one wavelength context: the straight seed's solution, if any.
    void solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
               const LightPoint& lp, const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k,
               SolutionSet& out) const;
    /// Alg. 2.
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain, int k,
                   const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda) const;
};

}  // namespace snell
