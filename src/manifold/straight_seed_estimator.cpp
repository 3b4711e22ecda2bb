#include "manifold/straight_seed_estimator.h"

namespace snell {

void StraightSeedEstimator::solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                  double pmf, const LightPoint& lp, const std::vector<ManifoldVertex>& seed,
                                  Sampler& sampler, int max_k, SolutionSet& out) const {
    HalfVectorDraws draws(sampler);
    if (q.straight_seed) add_solution(q, ctx, slot, light, pmf, lp, seed, draws, max_k, false, false, out);
}

double StraightSeedEstimator::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                      int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                                      double lambda) const {
    return alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
}

}  // namespace snell
