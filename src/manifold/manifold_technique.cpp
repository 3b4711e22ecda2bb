#include "manifold/manifold_technique.h"

#include <algorithm>

#include "manifold/all_solutions_estimator.h"
#include "manifold/fallback_estimator.h"
#include "manifold/keyed_trials_estimator.h"
#include "manifold/straight_seed_estimator.h"
#include "manifold/unbiased_estimator.h"

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
                                  int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                                  double lambda) const {
    return with_estimator(*m_scene, *m_settings, [&](const auto& estimator) {
        return estimator.density(xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
    });
}

}  // namespace snell
