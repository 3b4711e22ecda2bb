#include "manifold/keyed_trials_estimator.h"

#include <bit>

#include "manifold/seed_path.h"
#include "manifold/surface_seed.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

PCG32 keyed_trial_stream(const Vec3& xb, const Vec3& xc, double lambda) {
    uint64_t h = 0x6b657965645f7472ULL;
    for (const double v : {xb.x, xb.y, xb.z, xc.x, xc.y, xc.z, lambda}) h = mix_bits(h ^ std::bit_cast<uint64_t>(v));
    return PCG32(h, 0);
}

void KeyedTrialsEstimator::solve(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                 double pmf, const LightPoint& lp, const std::vector<ManifoldVertex>& seed,
                                 Sampler& sampler, int max_k, SolutionSet& out) const {
    const size_t before = out.solutions.size();
    HalfVectorDraws draws(sampler);
    if (q.straight_seed && walks_straight_seed())
        add_solution(q, ctx, slot, light, pmf, lp, seed, draws, max_k, false, true, out);
    // Each trial draws its caster from the keyed stream too, so the trials cost the same however
    // much glass the scene holds, and density() replays the same choices.
    const CasterChoice casters(*m_scene, q.xb->p, ctx.hero());
    PCG32 rng = keyed_trial_stream(q.xb->p, lp.p, ctx.hero());
    for (int j = 0; j < m_settings->trials && !casters.empty(); ++j) {
        // Traced about the shading normals and chosen without max_k, so that density() replays
        // the same choice from the path alone; add_solution drops too long a chain and the
        // solutions held already (the straight seed's among them).
        std::vector<ManifoldVertex> chain;
        if (!surface_trial(q, ctx, casters, rng, lp, draws, -1, &chain, /*trace_smooth=*/true)) continue;
        add_solution(q, ctx, slot, light, pmf, lp, std::move(chain), draws, max_k, true, true, out);
    }
    walk_counters::solutions_per_connection.add(uint32_t(out.solutions.size() - before));
}

double KeyedTrialsEstimator::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                     int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                                     double lambda) const {
    // A path through an emissive interface is the straight seed's alone (no surface seed
    // starts on or passes an emitter).
    if (passes_emitter(chain, k))
        return walks_straight_seed() ? alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda) : 0.0;
    const StraightSeed seed = trace_straight_seed(*m_scene, xb, xc, lambda, *m_settings);
    // The straight seed first (Alg. 2): it is the cheapest and most often the one.
    if (walks_straight_seed() && seed.status == SeedStatus::Refractive) {
        const double p = alg2_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed);
        if (p > 0) return p;
    }
    const double p_solution = every_solution_density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, &seed);
    if (!(p_solution > 0)) return 0;
    // Then the trials solve() made for this connection, replayed with the path's half vectors.
    std::vector<ManifoldVertex> target;
    std::vector<Vec2> slopes;
    if (!chain_of_path(xb, chain, k, xc, lambda, &target, &slopes)) return 0;
    const TangentBasis basis = light_point_basis(xc, nc, normalize(xc - xb.p));
    polish_solution(m_scene, xb.p, target, basis, m_settings->walk);
    HalfVectorDraws draws = HalfVectorDraws::of_unit_slopes(std::move(slopes));
    ManifoldQuery q;
    q.xb = &xb;
    q.bsdf_b = &bsdf_b;
    q.ctx = BSDFContext{SampledWavelengths::single(lambda, 1.0), TransportMode::Radiance};
    LightPoint lp;
    lp.p = xc;
    lp.n = nc;
    const CasterChoice casters(*m_scene, xb.p, lambda);
    PCG32 rng = keyed_trial_stream(xb.p, xc, lambda);
    for (int j = 0; j < m_settings->trials && !casters.empty(); ++j) {
        std::vector<ManifoldVertex> found;
        if (surface_trial(q, q.ctx, casters, rng, lp, draws, -1, &found, /*trace_smooth=*/true) &&
            same_solution(xb.p, found, target, xc))
            return p_solution;
    }
    return 0;
}

}  // namespace snell
