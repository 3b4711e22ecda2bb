#include "manifold/fallback_estimator.h"

#include "manifold/seed_path.h"
#include "manifold/surface_seed.h"
#include "manifold/walk_counters.h"

namespace snell {

void FallbackEstimator::solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light, double pmf,
                              const LightPoint& lp, const std::vector<ManifoldVertex>& seed, Sampler& sampler,
                              int max_k, SolutionSet& out) const {
    const size_t before = out.solutions.size();
    HalfVectorDraws draws(sampler);
    if (q.straight_seed) {
        add_solution(q, ctx, slot, light, pmf, lp, seed, draws, max_k, false, false, out);
        return;
    }
    // Blocked: the surface seeds run, their solutions counted as the unbiased estimator counts them.
    const Foreign none = [](const std::vector<ManifoldVertex>&) { return false; };
    PCG32 rng = trial_stream(sampler);
    const CasterChoice casters(*m_scene, q.xb->p, ctx.hero());
    if (!casters.empty())
        count_trials_to_refind(q, ctx, slot, light, pmf, lp, casters, rng, draws, max_k, none, before, out);
    walk_counters::solutions_per_connection.add(uint32_t(out.solutions.size() - before));
}

double FallbackEstimator::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                  int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                                  double lambda) const {
    if (passes_emitter(chain, k)) return alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
    // The straight seed's technique where the seed is clear of opaque surfaces (Alg. 2), the
    // surface seeds' where one blocks it; the seed is traced once for either.
    const StraightSeed s = trace_straight_seed(*m_scene, xb, xc, lambda, *m_settings);
    if (s.status == SeedStatus::Blocked)
        return every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &s);
    return alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &s);
}

}  // namespace snell
