#include "integrators/mnee/mnee_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/props.h"
#include "integrators/light_connection.h"
#include "integrators/mis.h"
#include "manifold/manifold_technique.h"
#include "manifold/mnee.h"
#include "manifold/seed_path.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

namespace {

// A string parameter naming one of `names` (the first is listed first in the error); `def` if
// absent.
template <typename E>
E choice(const Props& p, const std::string& name, E def, std::initializer_list<std::pair<const char*, E>> names) {
    if (!p.has(name)) return def;
    const std::string v = p.get_string(name);
    std::string list;
    for (const auto& [n, e] : names) {
        if (v == n) return e;
        list += (list.empty() ? "'" : ", '") + std::string(n) + "'";
    }
    p.raise_param(name, name + " must be one of " + list);
}

}  // namespace

MneeSettings MneeIntegrator::settings_from_props(const Props& p) {
    MneeSettings s;
    s.max_vertices = int(p.get_int("max_vertices", s.max_vertices));
    s.ignore_occluders = p.get_bool("ignore_occluders", s.ignore_occluders);
    s.cull_margin = p.get_float("cull_margin", s.cull_margin);
    s.biased = p.get_bool("biased", s.biased);
    s.spectral_walks = p.get_bool("spectral_walks", s.spectral_walks);
    s.walk.max_iterations = int(p.get_int("max_iterations", s.walk.max_iterations));
    s.walk.threshold = p.get_float("threshold", s.walk.threshold);
    s.walk.allow_error_increase = p.get_bool("allow_error_increase", s.walk.allow_error_increase);
    s.walk.min_step = p.get_float("min_step", s.walk.min_step);
    s.walk.stall_window = int(p.get_int("stall_window", s.walk.stall_window));
    s.walk.stall_ratio = p.get_float("stall_ratio", s.walk.stall_ratio);
    s.max_geometry = p.get_float("max_geometry", s.max_geometry);
    s.seeding = choice(p, "seeding", s.seeding,
                       {{"straight", MneeSeeding::Straight},
                        {"surface", MneeSeeding::Surface},
                        {"straight+surface", MneeSeeding::StraightAndSurface}});
    // The default is `unbiased` with the straight seed, surface seeds and surface_weight 0.03:
    // the best at equal time on the droplets and the glass sphere (docs/experiments.md). The
    // biased mode too (issue 26): with `fallback` its outlier rule dropped the post-fold branch
    // of a ball resting on a plane (0.38 of the caustic's mean); with the surface trials' solutions
    // it keeps 0.81-1.03 of the mean on the caustic gallery (fallback: 0.38-1.00), at lower
    // relMSE on 6 of its 10 cases, the others within 12 % (docs/experiments.md).
    // `solutions=one` is the paper's, as is `seeding=straight` alone.
    const MneeSolutions default_solutions =
        p.has("seeding") && s.seeding != MneeSeeding::StraightAndSurface ? MneeSolutions::One : MneeSolutions::Unbiased;
    s.solutions = choice(p, "solutions", default_solutions,
                         {{"one", MneeSolutions::One},
                          {"all", MneeSolutions::All},
                          {"unbiased", MneeSolutions::Unbiased},
                          {"fallback", MneeSolutions::Fallback}});
    // The estimators of several solutions walk both kinds of seeds unless told otherwise
    // (fallback: surface seeds where the straight one is blocked).
    if (s.solutions != MneeSolutions::One && !p.has("seeding")) s.seeding = MneeSeeding::StraightAndSurface;
    if (s.solutions == MneeSolutions::Fallback && s.seeding != MneeSeeding::StraightAndSurface)
        p.raise_param("seeding", "solutions=fallback takes seeding=straight+surface");
    // trials: surface seeds per caster for `all`; the first round M of `unbiased` (SMS's 1 / p
    // estimate is M = 1, its default: larger rounds lower the variance per sample about as much as
    // they raise its cost, on the glass sphere's caustic; docs/mnee.md).
    s.trials = int(p.get_int(
        "trials", s.solutions == MneeSolutions::Unbiased || s.solutions == MneeSolutions::Fallback ? 1 : s.trials));
    if (s.trials < 1) p.raise_param("trials", "trials must be >= 1");
    s.max_trials = int(p.get_int("max_trials", s.max_trials));
    if (s.max_trials < 1) p.raise_param("max_trials", "max_trials must be >= 1");
    // The paper's estimator counts the straight seed's solution alone; every other pairing
    // would silently drop the solutions its seeds do not reach.
    if (s.solutions == MneeSolutions::One && s.seeding != MneeSeeding::Straight)
        p.raise_param("seeding", "solutions=one takes the straight seed only; use solutions=all with surface seeds");
    if (s.solutions != MneeSolutions::One && s.seeding == MneeSeeding::Straight)
        p.raise_param("solutions", "solutions=" + p.get_string("solutions") +
                                       " needs surface seeds: seeding=surface or straight+surface");
    s.surface_side =
        choice(p, "surface_side", s.surface_side,
               {{"receiver", SurfaceSide::Receiver}, {"light", SurfaceSide::Light}, {"both", SurfaceSide::Both}});
    s.seed_candidates = int(p.get_int("seed_candidates", s.seed_candidates));
    if (s.seed_candidates < 1 || s.seed_candidates > 1024)
        p.raise_param("seed_candidates", "seed_candidates must lie in [1, 1024]");
    s.reflections = p.get_bool("reflections", s.reflections);
    // surface_weight 0.03: the best of 1, 0.3, 0.1, 0.03, 0.01 and 0.003 at equal time on the
    // droplets' caustics (docs/mnee.md); `all` counts each solution once (no 1 / p) and keeps 1.
    const bool both_seeds = (s.solutions == MneeSolutions::Unbiased || s.solutions == MneeSolutions::All) &&
                            s.seeding == MneeSeeding::StraightAndSurface;
    s.surface_weight =
        p.get_float("surface_weight", both_seeds && s.solutions == MneeSolutions::Unbiased ? kSurfaceWeight : 1.0);
    if (!(s.surface_weight > 0 && s.surface_weight <= 1))
        p.raise_param("surface_weight", "surface_weight must lie in (0, 1]");
    if (p.has("surface_weight") && !both_seeds)
        p.raise_param("surface_weight",
                      "surface_weight weighs the surface seeds' solutions against the straight seed's: it needs "
                      "solutions=all or unbiased with seeding=straight+surface");
    if (s.reflections && s.solutions == MneeSolutions::One)
        p.raise_param("reflections", "reflections need the surface seeds of solutions=all or unbiased");
    s.walk.projection = choice(p, "projection", s.walk.projection,
                               {{"closest_point", Projection::ClosestPoint}, {"raycast", Projection::RayCast}});
    if (s.max_vertices < 1 || s.max_vertices > RefractiveSuffix::kMaxVertices)
        p.raise_param("max_vertices",
                      "max_vertices must lie in [1, " + std::to_string(RefractiveSuffix::kMaxVertices) + "]");
    if (s.walk.max_iterations < 1) p.raise_param("max_iterations", "max_iterations must be >= 1");
    if (!(s.walk.threshold > 0)) p.raise_param("threshold", "threshold must be > 0");
    if (!(s.walk.min_step > 0 && s.walk.min_step <= 1)) p.raise_param("min_step", "min_step must lie in (0, 1]");
    if (s.walk.stall_window < 0 || s.walk.stall_window > kMaxStallWindow)
        p.raise_param("stall_window", "stall_window must lie in [0, " + std::to_string(kMaxStallWindow) + "]");
    if (!(s.walk.stall_ratio > 0 && s.walk.stall_ratio <= 1))
        p.raise_param("stall_ratio", "stall_ratio must lie in (0, 1]");
    if (!(s.cull_margin >= 0)) p.raise_param("cull_margin", "cull_margin must be >= 0");
    if (!(s.max_geometry >= 0)) p.raise_param("max_geometry", "max_geometry must be >= 0 (0: no clamp)");
    s.connect_probability = p.get_float("connect_probability", s.connect_probability);
    if (!(s.connect_probability > 0 && s.connect_probability <= 1))
        p.raise_param("connect_probability", "connect_probability must lie in (0, 1]");
    return s;
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
    const RefractiveSuffix& s = static_cast<const MneePathState&>(state).suffix;
    if (!s.has_xb || s.k == 0) return PathTracer::emitter_hit_weight(scene, state, light, p, n, d, ctx);
    // A BSDF-sampled path x_b, x_1..x_k (refractive), x_c: three techniques can produce it.
    const LightPoint lp = light_point_hit(scene, light, p, n, Vec2(), d, s.xb.p);  // densities only: no uv
    const double pmf = scene.light_sampler().pmf(&light);
    const size_t last = size_t(s.k - 1);
    const double p_bsdf = s.p_prefix * s.q_last * std::abs(dot(lp.n, d)) / length_squared(lp.p - s.chain[last].p);
    const double p_mnee = covers(s, true)
                              ? connect_probability(light) * ManifoldTechnique(scene, m_mnee)
                                                                 .density(s.xb, *s.xb.bsdf(), s.chain.data(), s.k,
                                                                          light, pmf, lp.p, lp.n, ctx.hero())
                              : 0.0;
    const double p_nee =
        s.specular[last] ? 0.0 : s.p_prefix * pmf * light_point_pdf(scene, light, s.chain[last].p, lp.p, lp.n);
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
    const RefractiveSuffix& s = static_cast<const MneePathState&>(state).suffix;
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
    const double p_mnee = covers(s, refracts)
                              ? connect_probability(*light) * ManifoldTechnique(scene, m_mnee)
                                                                  .density(s.xb, *s.xb.bsdf(), s.chain.data(), s.k,
                                                                           *light, pmf, lp.p, lp.n, ctx.hero())
                              : 0.0;
    if (m_mnee.biased && covers(s, refracts) && !(p_mnee > 0)) return {};
    return nee_estimate(si, bsdf, ctx, state.media, *ls, f, pmf, power_heuristic(p_nee, {p_bsdf, p_mnee}));
}

double MneeIntegrator::connect_probability(const Light& light) const {
    return light.is_delta() ? 1.0 : m_mnee.connect_probability;
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
    const double q_connect = connect_probability(*light);
    if (q_connect < 1 && !(sampler.next_1d() < q_connect)) return;
    // Lines 3-5 (half vectors, walk, measurement) for every solution the technique finds; then
    // MIS of each against the other techniques that produce the same path.
    const ManifoldQuery q{&si,
                          &bsdf,
                          ctx,
                          state.media,
                          state.hero_only,
                          /*straight_seed=*/status == SeedStatus::Refractive};
    const SolutionSet set = ManifoldTechnique(scene, m_mnee).solve(q, *light, pmf, lp, chain, sampler, max_k);
    for (const ManifoldSolution& sol : set.solutions)
        out.add(sol.from_surface ? Technique::MneeSurface : Technique::MneeStraight,
                sol.value * (sol.count * power_heuristic(q_connect * sol.density, {sol.pdf_bsdf, sol.pdf_nee_last}) /
                             q_connect));
}

}  // namespace snell
