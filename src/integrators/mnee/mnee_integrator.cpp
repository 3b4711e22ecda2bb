#include "integrators/mnee/mnee_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/props.h"
#include "integrators/light_connection.h"
#include "integrators/mis.h"
#include "integrators/mnee/work_meter.h"
#include "manifold/manifold_technique.h"
#include "manifold/mnee.h"
#include "manifold/seed_path.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

namespace {

/// The `mnee` integrator's tracer with a learned allocation: the first pilot_spp samples of
/// every pixel run at the pilot's q and record what ConnectionAllocation needs; after the pass
/// that completes them, every sample runs at its region's q.
class MneeTracer final : public SampleTracer {
public:
    MneeTracer(const MneeIntegrator& mnee, const FilmSpec& film)
        : m_mnee(mnee),
          m_pilot_spp(uint64_t(mnee.mnee_settings().pilot_spp)),
          m_allocation(std::make_unique<ConnectionAllocation>(film.out_width(), film.out_height(), film.crop_x,
                                                              film.crop_y, mnee.mnee_settings().allocation_block,
                                                              mnee.mnee_settings().connect_probability)) {}

    SampledSpectrum li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                             SplatList& /*splats*/) const override {
        const int x = int(std::floor(cs.pixel_centre.x)), y = int(std::floor(cs.pixel_centre.y));
        MneePathState state;
        state.q = m_allocation->q(x, y);
        if (!m_allocation->learning()) return m_mnee.li(ray, scene, sampler, cs.wl, state);
        // A pilot sample: its pixel's statistics are written by the one thread rendering it.
        PilotSample record;
        state.pilot = &record;
        const double w0 = work_so_far();
        const SampledSpectrum L = m_mnee.li(ray, scene, sampler, cs.wl, state);
        m_allocation->add(x, y, record, L.average(), work_so_far() - w0);
        return L;
    }
    void end_pass(uint64_t samples_per_pixel) override {
        if (!m_allocation->learning() || samples_per_pixel < m_pilot_spp) return;
        m_allocation->fit();
        const auto h = m_allocation->histogram();
        for (size_t j = 0; j < h.size(); ++j) walk_counters::allocation_regions.add(int64_t(j), h[j]);
    }
    double max_sample_share() const override { return m_mnee.settings().max_sample_share; }
    int clamp_spread() const override { return m_mnee.settings().clamp_spread; }
    std::vector<std::string> technique_names() const override { return path_technique_names(); }

private:
    const MneeIntegrator& m_mnee;
    uint64_t m_pilot_spp;
    std::unique_ptr<ConnectionAllocation> m_allocation;  ///< pointer: li_splat() is const
};

}  // namespace

std::unique_ptr<SampleTracer> MneeIntegrator::prepare(const Scene& scene, const FilmSpec& film,
                                                      const RenderOptions& options) const {
    if (!m_mnee.learned_allocation) return PathTracer::prepare(scene, film, options);
    return std::make_unique<MneeTracer>(*this, film);
}

PathSettings MneeIntegrator::path_settings_from_props(const Props& p) {
    PathSettings s = PathSettings::tracer_from_props(p);
    if (p.get_bool("biased", false) && !p.has("max_sample_share")) s.max_sample_share = kBiasedMaxSampleShare;
    if (p.get_bool("biased", false) && !p.has("clamp_spread")) s.clamp_spread = kBiasedClampSpread;
    return s;
}

void MneeIntegrator::on_arrival(PathState& state, const SurfaceInteraction& si, const Ray& ray,
                                const BSDFContext& ctx) const {
    RefractiveSuffix& s = static_cast<MneePathState&>(state).suffix;
    if (!s.has_xb || !is_manifold_interface(si.bsdf(), ctx.hero())) return;
    if (s.k >= RefractiveSuffix::kMaxVertices) {
        s.has_xb = false;
        return;
    }
    // Area density of reaching this vertex: solid-angle density times |cos| / d^2.
    s.p_prefix *= s.q_last * std::abs(dot(si.ng, ray.d)) / (si.t * si.t);
    s.chain[size_t(s.k++)] = si;
}

void MneeIntegrator::on_scatter(PathState& state, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                                const BSDFContext& ctx) const {
    RefractiveSuffix& s = static_cast<MneePathState&>(state).suffix;
    const MediumStack media_before = state.media;
    PathTracer::on_scatter(state, si, bsdf, bs, ctx);
    if (is_manifold_interface(&bsdf, ctx.hero())) {
        if (!s.has_xb) return;
        const size_t i = size_t(s.k - 1);
        s.specular[i] = bs.is_delta();
        if (!(bs.lobe & kTransmission)) s.transmissions_only = false;
        const ManifoldVertex v = ManifoldVertex::from_interaction(si, bsdf.eta(ctx.hero()));
        s.q_last = vertex_bsdf_density(v, si.wo, bs.wi, ctx);
    } else if (bsdf.is_smooth_sampled() && !bs.is_delta()) {
        // A new x_b: MNEE connected from here.
        s = RefractiveSuffix();
        s.has_xb = true;
        s.xb = si;
        s.xb_media = media_before;
        s.q_last = bs.pdf;
    } else {
        s.has_xb = false;
    }
}

double MneeIntegrator::emitter_hit_weight(const Scene& scene, const PathState& state, const Light& light, const Vec3& p,
                                          const Vec3& n, const Vec3& d, const BSDFContext& ctx) const {
    const MneePathState& ms = static_cast<const MneePathState&>(state);
    const RefractiveSuffix& s = ms.suffix;
    if (!s.has_xb || s.k == 0) return PathTracer::emitter_hit_weight(scene, state, light, p, n, d, ctx);
    // A BSDF-sampled path x_b, x_1..x_k (refractive), x_c: three techniques can produce it.
    const LightPoint lp = light_point_hit(scene, light, p, n, Vec2(), d, s.xb.p);  // densities only: no uv
    const double pmf = scene.light_sampler().pmf(&light);
    const size_t last = size_t(s.k - 1);
    const double p_bsdf = s.p_prefix * s.q_last * std::abs(dot(lp.n, d)) / length_squared(lp.p - s.chain[last].p);
    const double q = connect_probability(light, state);
    const double p_m = mnee_density(scene, ms, true, light, pmf, lp.p, lp.n, q, ctx.hero());
    const double p_mnee = q * p_m;
    const double p_nee =
        s.specular[last] ? 0.0 : s.p_prefix * pmf * light_point_pdf(scene, light, s.chain[last].p, lp.p, lp.n);
    if (ms.pilot && p_m > 0) ms.pilot->add_other(state.emitter_value.average(), p_bsdf, p_m, p_bsdf + p_nee, q);
    // Sec. 3.5: outlier removal drops the light that BSDF sampling finds through interfaces after
    // x_b but MNEE cannot: transmissive suffixes its walks do not reach, and suffixes with an
    // internal reflection (rare, bright hits through the glass: fireflies that no sample count
    // averages away).
    if (m_mnee.biased && !(p_mnee > 0)) return 0.0;
    return power_heuristic(p_bsdf, {p_mnee, p_nee});
}

SampledSpectrum MneeIntegrator::connect_at_interface(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                                     const BSDFContext& ctx, const PathState& state,
                                                     Sampler& sampler) const {
    const MneePathState& ms = static_cast<const MneePathState&>(state);
    const RefractiveSuffix& s = ms.suffix;
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, si, ctx.wl, sampler, &light, &pmf);
    if (!ls) return {};
    if (!s.has_xb || s.k == 0) return nee_connect(scene, si, bsdf, ctx, state.media, *ls, pmf);
    const Vec3 wo = si.to_local(si.wo), wi = si.to_local(ls->wi);
    const SampledSpectrum f = bsdf.eval(ctx.at(si), wo, wi);
    if (f.is_zero()) return {};
    const Ray shadow = std::isinf(ls->dist) ? scene.spawn_ray(si, ls->wi) : scene.spawn_ray_to(si, ls->p, ls->p_error);
    if (scene.occluded(shadow)) return {};
    // The path x_b, x_1..x_k = si, x_c in area measure (lights at infinity on MNEE's far sphere).
    const LightPoint lp = light_point_hit(scene, *light, ls->p, ls->n, ls->uv, ls->wi, s.xb.p);
    const double p_nee = s.p_prefix * pmf * light_point_pdf(scene, *light, si.p, lp.p, lp.n);
    const double p_bsdf = lp.delta ? 0.0
                                   : s.p_prefix * bsdf.pdf(ctx.at(si), wo, wi) * std::abs(dot(lp.n, ls->wi)) /
                                         length_squared(lp.p - si.p);
    const bool refracts = dot(si.wo, si.ng) * dot(ls->wi, si.ng) < 0;
    const double q = connect_probability(*light, state);
    const double p_m = mnee_density(scene, ms, refracts, *light, pmf, lp.p, lp.n, q, ctx.hero());
    const double p_mnee = q * p_m;
    if (m_mnee.biased && covers(s, refracts) && !(p_mnee > 0)) return {};
    const SampledSpectrum unweighted = nee_estimate(si, bsdf, ctx, state.media, *ls, f, pmf, 1.0);
    if (ms.pilot && p_m > 0 && !light->is_delta())
        ms.pilot->add_other((state.beta * unweighted).average(), p_nee, p_m, p_nee + p_bsdf, q);
    return unweighted * power_heuristic(p_nee, {p_bsdf, p_mnee});
}

double MneeIntegrator::mnee_density(const Scene& scene, const MneePathState& state, bool last_refracts,
                                    const Light& light, double pmf, const Vec3& p, const Vec3& n, double q,
                                    double lambda) const {
    const RefractiveSuffix& s = state.suffix;
    // q = 0: the region leaves these paths to BSDF sampling, and MIS needs no density (nor its walk).
    if (!covers(s, last_refracts) || !(q > 0)) return 0.0;
    const double w0 = state.pilot ? work_so_far() : 0.0;
    const double d =
        ManifoldTechnique(scene, m_mnee).density(s.xb, *s.xb.bsdf(), s.chain.data(), s.k, light, pmf, p, n, lambda);
    if (state.pilot) state.pilot->work_density += work_so_far() - w0;
    return d;
}

double MneeIntegrator::connect_probability(const Light& light, const PathState& state) const {
    if (light.is_delta()) return 1.0;
    const double q = static_cast<const MneePathState&>(state).q;
    return q >= 0 ? q : m_mnee.connect_probability;
}

bool MneeIntegrator::covers(const RefractiveSuffix& s, bool last_refracts) const {
    if (m_mnee.reflections && m_mnee.solutions != MneeSolutions::One) return true;
    return s.transmissions_only && last_refracts;
}

Technique MneeIntegrator::emitter_hit_technique(const PathState& state) const {
    const RefractiveSuffix& s = static_cast<const MneePathState&>(state).suffix;
    if (!s.has_xb || s.k == 0) return Technique::BsdfHit;
    return s.transmissions_only ? Technique::BsdfRefracted : Technique::BsdfReflected;
}

void MneeIntegrator::connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                      const BSDFContext& ctx, const PathState& state, Sampler& sampler,
                                      LightConnection& out) const {
    if (is_manifold_interface(&bsdf, ctx.hero())) {
        out.add(Technique::Nee, connect_at_interface(scene, si, bsdf, ctx, state, sampler));
        return;
    }

    // Alg. 1, line 1: the light point, drawn exactly as NEE draws it.
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, si, ctx.wl, sampler, &light, &pmf, /*keep_dark=*/true);
    if (!ls) return;
    const double q_connect = connect_probability(*light, state);
    if (!(q_connect > 0)) {
        // This region leaves the refracted light to BSDF sampling (ConnectionAllocation): what
        // is left of the connection is NEE's, one shadow ray (a seed that meets glass gives 0).
        const SampledSpectrum f = bsdf.eval(ctx.at(si), si.to_local(si.wo), si.to_local(ls->wi));
        const Ray shadow =
            std::isinf(ls->dist) ? scene.spawn_ray(si, ls->wi) : scene.spawn_ray_to(si, ls->p, ls->p_error);
        if (f.is_nonzero() && !scene.occluded(shadow))
            out.add(Technique::Nee,
                    nee_estimate(si, bsdf, ctx, state.media, *ls, f, pmf, nee_weight(si, bsdf, ctx, *ls, pmf)));
        return;
    }
    const LightPoint lp = light_point(scene, *light, *ls, si.p);

    // Line 2: the seed path (Sec. 3.1).
    std::vector<ManifoldVertex> chain;
    const SeedStatus status = trace_seed_path(scene, si, lp.p, ctx.hero(), m_mnee, &chain);
    switch (status) {
        case SeedStatus::Clear:
            // Nothing refracts in between: MNEE is NEE (same sample, same weight).
            {
                const SampledSpectrum f = bsdf.eval(ctx.at(si), si.to_local(si.wo), si.to_local(ls->wi));
                if (f.is_nonzero())
                    out.add(Technique::Nee,
                            nee_estimate(si, bsdf, ctx, state.media, *ls, f, pmf, nee_weight(si, bsdf, ctx, *ls, pmf)));
                return;
            }
        case SeedStatus::Occluded:
            ++walk_counters::seeds_occluded;
            return;
        case SeedStatus::BlockedRefractive:
            // (Multi-solution estimators only.) The straight seed is blocked; the surface seeds
            // may still find refracted paths around the blocker (an object inside glass).
            ++walk_counters::seeds_occluded;
            break;
        case SeedStatus::TooMany:
            ++walk_counters::seeds_too_many;
            return;
        case SeedStatus::Refractive:
            break;
    }
    // The connection adds k + 1 segments to the depth + 1 the path has (max_depth, Mitsuba's
    // meaning); BSDF sampling cannot produce longer paths, so neither may MNEE.
    const int max_k = m_settings.max_depth >= 0 ? m_settings.max_depth - state.depth - 2 : -1;
    if (m_mnee.solutions == MneeSolutions::One && max_k >= 0 && int(chain.size()) > max_k) return;
    // connect_probability q: the connection is made with probability q, counted 1 / q, and MIS
    // weighs it by its density q p_mnee (BSDF sampling's paths are weighed the same way above,
    // in emitter_hit_weight and connect_at_interface).
    if (q_connect < 1 && !(sampler.next_1d() < q_connect)) return;
    // Lines 3-5 (half vectors, walk, measurement) for every solution the technique finds; then
    // MIS of each against the other techniques that produce the same path.
    const ManifoldQuery q{&si,
                          &bsdf,
                          ctx,
                          state.media,
                          state.hero_only,
                          /*straight_seed=*/status == SeedStatus::Refractive};
    // Delta lights keep q = 1 in every region: their connections are no part of the choice.
    PilotSample* pilot = light->is_delta() ? nullptr : static_cast<const MneePathState&>(state).pilot;
    const double w0 = pilot ? work_so_far() : 0.0;
    const SolutionSet set = ManifoldTechnique(scene, m_mnee).solve(q, *light, pmf, lp, chain, sampler, max_k);
    if (pilot) {
        pilot->work_connect += work_so_far() - w0;
        for (const ManifoldSolution& sol : set.solutions)
            pilot->add_connection((state.beta * sol.value * sol.count).average(), sol.density,
                                  sol.pdf_bsdf + sol.pdf_nee_last, q_connect);
    }
    for (const ManifoldSolution& sol : set.solutions)
        out.add(sol.from_surface ? Technique::MneeSurface : Technique::MneeStraight,
                sol.value * (sol.count * power_heuristic(q_connect * sol.density, {sol.pdf_bsdf, sol.pdf_nee_last}) /
                             q_connect));
}

}  // namespace snell
