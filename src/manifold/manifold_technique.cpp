#include "manifold/manifold_technique.h"

#include <algorithm>

namespace snell {

SolutionSet ManifoldTechnique::solve(const ManifoldQuery& q, const Light& light, double pmf, const LightPoint& lp,
                                     const std::vector<ManifoldVertex>& seed, Sampler& sampler) const {
    SolutionSet out;
    const bool dispersive =
        std::any_of(seed.begin(), seed.end(), [](const ManifoldVertex& v) { return v.bsdf->dispersive(); });
    if (dispersive && m_settings->spectral_walks && q.ctx.wl.count() > 1 && !q.hero_only) {
        for (int i = 0; i < q.ctx.wl.count(); ++i) {
            std::vector<ManifoldVertex> chain = seed;
            for (ManifoldVertex& v : chain) v.eta = v.bsdf->eta(q.ctx.wl[i]);
            const BSDFContext ctx_i{SampledWavelengths::single(q.ctx.wl[i], q.ctx.wl.pdf(i)), q.ctx.mode};
            solve_once(q, ctx_i, i, light, pmf, lp, std::move(chain), sampler, out);
        }
        return out;
    }
    solve_once(q, q.ctx, -1, light, pmf, lp, seed, sampler, out);
    return out;
}

void ManifoldTechnique::solve_once(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                   double pmf, const LightPoint& lp, std::vector<ManifoldVertex> chain,
                                   Sampler& sampler, SolutionSet& out) const {
    const MneeConnection c =
        mnee_connect(*m_scene, *m_settings, *q.xb, *q.bsdf_b, ctx, q.media, light, pmf, lp, chain, sampler);
    if (c.outcome != MneeOutcome::Success) return;
    ManifoldSolution s;
    s.chain = std::move(chain);
    s.slot = slot;
    if (slot >= 0) {
        s.value[slot] = c.value[0];
    } else {
        // A dispersive chain solved for the hero alone (no per-wavelength walks): scale the hero
        // once, unless the path's throughput already did.
        s.hero_only = c.hero_only && !q.hero_only;
        s.value = s.hero_only ? q.ctx.wl.hero_only(c.value) : c.value;
    }
    s.density = c.pdf_mnee;
    s.pdf_bsdf = c.pdf_bsdf;
    s.pdf_nee_last = c.pdf_nee_last;
    out.solutions.push_back(std::move(s));
}

double ManifoldTechnique::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                  int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                                  double lambda) const {
    return mnee_pdf(*m_scene, *m_settings, xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda);
}

}  // namespace snell
