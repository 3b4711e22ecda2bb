#include "integrators/light_connection.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "core/sampler.h"
#include "integrators/mis.h"
#include "integrators/scatter.h"
#include "light/light.h"
#include "scene/caster_sampling.h"
#include "scene/scene.h"

namespace snell {

SampledSpectrum nee_estimate(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                             const MediumStack& path_media, const LightSample& ls, const SampledSpectrum& f, double pmf,
                             double w) {
    // Unoccluded, so the shadow segment lies entirely in one medium: the current one, or the
    // one on the other side when the light is reached by refracting here (rough dielectrics).
    const MediumStack media = medium_towards(path_media, si, bsdf, ls.wi, ctx.hero());
    const SampledSpectrum tr = media.inside() ? media.transmittance(ls.dist, ctx.wl) : SampledSpectrum(1.0);
    return f * tr * ls.Le * (std::abs(dot(si.n, ls.wi)) * w / (pmf * ls.pdf));
}

double nee_weight(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, const LightSample& ls,
                  double pmf, double light_share, double bsdf_share, const CasterSampling* directions) {
    // Delta lights cannot be hit by BSDF sampling.
    if (ls.delta) return 1.0;
    const Vec3 wo = si.to_local(si.wo), wi = si.to_local(ls.wi);
    const double p_bsdf = directions ? directions->pdf(si, bsdf, ctx.at(si), wo, wi) : bsdf.pdf(ctx.at(si), wo, wi);
    return power_heuristic(light_share * pmf * ls.pdf, bsdf_share * p_bsdf);
}

namespace {
SampledSpectrum connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                        const MediumStack& media, const LightSample& ls, double pmf, double light_share,
                        double bsdf_share, const CasterSampling* directions) {
    const SampledSpectrum f = bsdf.eval(ctx.at(si), si.to_local(si.wo), si.to_local(ls.wi));
    if (f.is_zero()) return {};
    if (!light_visible(scene, si, ls)) return {};
    return nee_estimate(si, bsdf, ctx, media, ls, f, pmf,
                        nee_weight(si, bsdf, ctx, ls, pmf, light_share, bsdf_share, directions));
}
}  // namespace

SampledSpectrum nee_connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                            const MediumStack& media, const LightSample& ls, double pmf, double light_share,
                            double bsdf_share) {
    return connect(scene, si, bsdf, ctx, media, ls, pmf, light_share, bsdf_share, nullptr);
}

SampledSpectrum nee_connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                            const MediumStack& media, const LightSample& ls, double pmf,
                            const CasterSampling& directions) {
    return connect(scene, si, bsdf, ctx, media, ls, pmf, 1, 1, &directions);
}

}  // namespace snell
