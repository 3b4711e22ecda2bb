#include "manifold/manifold_technique.h"

#include <algorithm>
#include <type_traits>

#include "manifold/all_solutions_estimator.h"
#include "manifold/fallback_estimator.h"
#include "manifold/keyed_trials_estimator.h"
#include "manifold/seed_path.h"
#include "manifold/straight_seed_estimator.h"
#include "manifold/unbiased_estimator.h"
#include "manifold/walk_counters.h"
#include "manifold/work_meter.h"
#include "scene/scene.h"

namespace snell {

namespace {

// Runs `f` with the estimator the settings name (one class per estimator; each is a pair of
// pointers, built on the stack per call).
template <typename F>
auto with_estimator(const Scene& scene, const MneeSettings& st, F&& f) {
    switch (st.solutions) {
        case MneeSolutions::One:
            return f(StraightSeedEstimator(scene, st));
        case MneeSolutions::All:
            return f(AllSolutionsEstimator(scene, st));
        case MneeSolutions::Unbiased:
            return f(UnbiasedEstimator(scene, st));
        case MneeSolutions::Fallback:
            return f(FallbackEstimator(scene, st));
        case MneeSolutions::Keyed:
            return f(KeyedTrialsEstimator(scene, st));
    }
    return f(StraightSeedEstimator(scene, st));
}

}  // namespace

ManifoldConnection ManifoldTechnique::connect(const ManifoldQuery& query, Sampler& sampler) const {
    ManifoldConnection c;
    const Scene& scene = *m_scene;
    const SurfaceInteraction& xb = *query.xb;
    // Line 1: the light point. Dark samples are kept: MNEE reaches the light along another
    // direction than the straight one (a spot light seen from outside its cone).
    const auto ls = sample_light(scene, xb, query.ctx.wl, sampler, &c.light, &c.pmf, /*keep_dark=*/true);
    if (!ls) return c;
    c.ls = *ls;
    c.q = c.light->is_delta() ? 1.0 : query.connect_probability;
    // x_b's BSDF towards the sample, for the case the connection turns out to be NEE's.
    const auto f_b = [&] { return query.bsdf_b->eval(query.ctx.at(xb), xb.to_local(xb.wo), xb.to_local(ls->wi)); };
    // The connection is made with probability q (and counted 1 / q by the caller); the coin
    // comes first, so that a region at small q does not trace a seed it will not walk. Without
    // the connection the region leaves the refracted light to BSDF sampling: what is left is
    // NEE's, one shadow ray (a segment that meets glass gives 0), the same sample as a clear seed.
    if (!(c.q > 0) || (c.q < 1 && !(sampler.next_1d() < c.q))) {
        c.f_b = f_b();
        if (c.f_b.is_nonzero() && light_visible(scene, xb, *ls)) c.kind = ManifoldConnection::Kind::Direct;
        return c;
    }
    const LightPoint lp = light_point(scene, *c.light, *ls, xb.p);

    // Line 2: the seed path.
    std::vector<ManifoldVertex> seed;
    const double w_seed = query.meter_work ? work_so_far() : 0.0;
    const SeedStatus status = trace_seed_path(scene, xb, lp.p, query.ctx.hero(), *m_settings, &seed);
    if (query.meter_work) c.seed_work = work_so_far() - w_seed;
    switch (status) {
        case SeedStatus::Clear:
            // Nothing refracts in between: MNEE is NEE (same sample, same weight).
            c.f_b = f_b();
            if (c.f_b.is_nonzero()) c.kind = ManifoldConnection::Kind::Direct;
            return c;
        case SeedStatus::Occluded:
            ++walk_counters::seeds_occluded;
            return c;
        case SeedStatus::Blocked:
            // (Multi-solution estimators only.) The straight seed is blocked; the surface seeds
            // may still find refracted paths around the blocker (an object inside glass).
            ++walk_counters::seeds_occluded;
            break;
        case SeedStatus::TooMany:
            ++walk_counters::seeds_too_many;
            return c;
        case SeedStatus::Refractive:
            break;
    }
    if (m_settings->solutions == MneeSolutions::One && query.max_k >= 0 && int(seed.size()) > query.max_k) return c;
    // Lines 3-5 (half vectors, walk, measurement) for every solution the estimator finds.
    ManifoldQuery q = query;
    q.straight_seed = status == SeedStatus::Refractive;
    q.cutoff_q = query.meter_work ? 0.0 : c.q;
    const double w0 = query.meter_work ? work_so_far() : 0.0;
    c.set = solve(q, *c.light, c.pmf, lp, seed, sampler, query.max_k);
    if (query.meter_work) c.work = work_so_far() - w0 - c.set.probe_work;
    c.kind = ManifoldConnection::Kind::Manifold;
    return c;
}

SolutionSet ManifoldTechnique::solve(const ManifoldQuery& q, const Light& light, double pmf, const LightPoint& lp,
                                     const std::vector<ManifoldVertex>& seed, Sampler& sampler, int max_k) const {
    SolutionSet out;
    with_estimator(*m_scene, *m_settings, [&](const auto& estimator) {
        const bool dispersive =
            std::any_of(seed.begin(), seed.end(), [](const ManifoldVertex& v) { return v.bsdf->dispersive(); });
        if (dispersive && m_settings->spectral_walks && q.ctx.wl.count() > 1 && !q.hero_only) {
            for (int i = 0; i < q.ctx.wl.count(); ++i) {
                std::vector<ManifoldVertex> chain = seed;
                for (ManifoldVertex& v : chain) v.eta = v.bsdf->eta(q.ctx.wl[i]);
                const BSDFContext ctx_i{SampledWavelengths::single(q.ctx.wl[i], q.ctx.wl.pdf(i)), q.ctx.mode};
                estimator.solve(q, ctx_i, i, light, pmf, lp, chain, sampler, max_k, out);
            }
            return 0;
        }
        estimator.solve(q, q.ctx, -1, light, pmf, lp, seed, sampler, max_k, out);
        return 0;
    });
    return out;
}

double ManifoldTechnique::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                  int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                                  bool surface_trials, DensityDetail* detail, bool failed_walk_trials) const {
    return with_estimator(*m_scene, *m_settings, [&](const auto& estimator) {
        // Only the multi-solution estimators weigh their surface solutions apart.
        if constexpr (std::is_base_of_v<MultiSolutionEstimator, std::decay_t<decltype(estimator)>>)
            return estimator.density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, surface_trials, detail,
                                     failed_walk_trials);
        else
            return estimator.density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
    });
}

}  // namespace snell
