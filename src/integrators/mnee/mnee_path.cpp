#include "integrators/mnee/mnee_path.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/sampler.h"
#include "core/stats.h"
#include "integrators/light_connection.h"
#include "integrators/mis.h"
#include "manifold/light_point.h"
#include "manifold/mis_cutoff.h"
#include "manifold/mnee.h"
#include "manifold/seed_path.h"
#include "manifold/work_meter.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

namespace snell {

namespace {
// Where MNEE's light comes from along the camera path (issue 26, the demo's fireflies): the
// luminance of each solution's weighted contribution, by the index of x_b on the path (1: the
// camera ray's hit). Their moments split the estimator's second moment by path length.
StatMoments by_vertex[] = {
    {"mnee.contribution.vertex_1", "luminance of MNEE solutions connected from the path's vertex 1"},
    {"mnee.contribution.vertex_2", "luminance of MNEE solutions connected from the path's vertex 2"},
    {"mnee.contribution.vertex_3", "luminance of MNEE solutions connected from the path's vertex 3"},
    {"mnee.contribution.vertex_4", "luminance of MNEE solutions connected from the path's vertex 4"},
    {"mnee.contribution.vertex_5", "luminance of MNEE solutions connected from the path's vertex 5"},
    {"mnee.contribution.vertex_6", "luminance of MNEE solutions connected from the path's vertex 6"},
    {"mnee.contribution.vertex_7+", "luminance of MNEE solutions connected from the path's vertex 7 or later"}};
}  // namespace

MneePath::MneePath(const Scene& scene, const PathSettings& path, const MneeSettings& mnee, const SampledWavelengths& wl,
                   const Ray& camera_ray, PathObserver* observer, double q, PilotSample* pilot, bool surface_trials,
                   bool failed_walk_trials)
    : m_scene(&scene),
      m_path(&path),
      m_mnee(&mnee),
      m_technique(scene, mnee),
      m_reflection(scene, mnee),
      m_ctx{wl, TransportMode::Radiance},
      m_walk(scene, path, wl, camera_ray, observer),
      m_q(q),
      m_pilot(pilot),
      m_surface_trials(surface_trials),
      m_failed_walk_trials(failed_walk_trials),
      // The reflected connection is made in every region. Delta lights keep q = 1 in every region
      // (ManifoldTechnique::connect), so NEE at a rough interface is weighed against MNEE for
      // them even where q = 0.
      m_reflects(ExteriorReflection::made(scene, mnee)),
      m_weighs_mnee(q != 0 || scene.has_delta_lights()) {
    m_prev.at = {camera_ray.o, Vec3()};
}

SampleEstimate MneePath::trace(Sampler& sampler) {
    ++render_stats::paths;
    const Scene& scene = *m_scene;
    const SampledWavelengths& wl = m_ctx.wl;
    CameraWalk& walk = m_walk;
    SurfaceInteraction si;  // overwritten by every hit
    for (;; ++walk.depth) {
        // The emitter's weight depends on the path *before* this vertex (it ends here), so it
        // is computed before the vertex joins the suffix.
        if (!walk.trace(&si)) {
            if (walk.emitters_visible())
                for (const Light* light : scene.infinite_lights()) {
                    const SampledSpectrum le = light->le_escaped(walk.ray.d, wl);
                    walk.add_emission(m_out, emitter_technique(), le, [&] {
                        return emitter_weight(*light, Vec3(), Vec3(), walk.ray.d, walk.tp.beta * le);
                    });
                }
            break;
        }
        if (const Light* em = si.emitter(); em && walk.emitters_visible()) {
            const SampledSpectrum le = em->le(si.p, si.n, si.uv, -walk.ray.d, wl);
            walk.add_emission(m_out, emitter_technique(), le,
                              [&] { return emitter_weight(*em, si.p, si.n, walk.ray.d, walk.tp.beta * le); });
        }
        arrive(si);
        const BSDF* bsdf = si.bsdf();
        if (!walk.may_scatter() || !bsdf) break;
        const BSDFContext sctx = m_ctx.at(si);  // textures are read at this vertex
        if (bsdf->is_smooth_sampled()) connect(si, *bsdf, sctx, sampler);
        const MediumStack media_before = walk.media;
        const auto bs = walk.scatter(si, *bsdf, sctx, sampler);
        if (!bs) break;
        m_prev.record(si, *bs);
        scattered(si, *bsdf, *bs, media_before);
    }
    return m_out.finish(wl);
}

void MneePath::connect(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx, Sampler& sampler) {
    const SampledSpectrum& beta = m_walk.tp.beta;
    if (is_manifold_interface(&bsdf, m_ctx.hero())) {
        m_out.add(Technique::Nee, beta * connect_at_interface(si, bsdf, sctx, sampler));
        return;
    }
    if (m_reflects) connect_reflected(si, bsdf, sctx, sampler);
    // Alg. 1 from x_b = si.
    ManifoldQuery query = query_at(si, bsdf, sctx);
    query.connect_probability = m_q >= 0 ? m_q : m_mnee->connect_probability;
    query.meter_work = m_pilot != nullptr;
    query.probes = m_pilot != nullptr;
    query.surface_trials = m_surface_trials;
    query.failed_walk_trials = m_failed_walk_trials;
    const ManifoldConnection c = m_technique.connect(query, sampler);
    // q = 0 would have made one shadow ray in place of the seed (ManifoldTechnique::connect).
    if (m_pilot && c.light && !c.light->is_delta() && c.seed_work > 0) m_pilot->work_seed += c.seed_work - 1.0;
    switch (c.kind) {
        case ManifoldConnection::Kind::None:
            return;
        case ManifoldConnection::Kind::Direct:
            // NEE's sample, with NEE's weight.
            m_out.add(Technique::Nee,
                      beta * nee_estimate(si, bsdf, sctx, m_walk.media, c.ls, c.f_b, c.pmf,
                                          nee_weight(si, bsdf, sctx, c.ls, c.pmf, 1, 1, &m_walk.directions())));
            return;
        case ManifoldConnection::Kind::Manifold:
            break;
    }
    // Delta lights keep q = 1 in every region: their connections are no part of the choice.
    if (m_pilot && !c.light->is_delta()) {
        m_pilot->work_connect += c.work;
        m_pilot->work_trials += c.set.trial_work;
        // The surface trials' solutions are the paths only they reach (the straight seed's own
        // is never added twice).
        // Those mis_cutoff leaves no weight too: the model weighs every candidate q without it.
        for (const ManifoldSolution& sol : c.set.solutions)
            m_pilot->add_connection((beta * sol.value * sol.count).average(), sol.count, sol.density, sol.weight,
                                    sol.pdf_bsdf + sol.pdf_nee_last, c.q, sol.from_surface);
        m_pilot->work_probe += c.set.probe_work;
        for (const ManifoldSolution& sol : c.set.probes)
            m_pilot->add_probe((beta * sol.value * sol.count).average(), sol.count, sol.density,
                               sol.pdf_bsdf + sol.pdf_nee_last, c.q);
    }
    // Each solution weighed against the techniques that produce the same path: the connection was
    // made with probability q, so it counts 1 / q and its density is q p_mnee (BSDF sampling's
    // paths are weighed the same way in emitter_weight and connect_at_interface).
    for (const ManifoldSolution& sol : c.set.solutions) {
        if (cut_off(sol, c.q)) {
            ++walk_counters::mis_cut_solutions;
            continue;
        }
        const SampledSpectrum v =
            beta * sol.value * (sol.count * power_heuristic(c.q * sol.density, {sol.pdf_bsdf, sol.pdf_nee_last}) / c.q);
        by_vertex[std::min<size_t>(size_t(m_walk.depth), std::size(by_vertex) - 1)].add(m_ctx.wl.to_xyz(v).y);
        m_out.add(sol.from_surface ? Technique::MneeSurface : Technique::MneeStraight, v);
    }
}

ManifoldQuery MneePath::query_at(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx) const {
    ManifoldQuery query{&si, &bsdf, sctx, m_walk.media, m_walk.tp.hero_only};
    // The connection adds k + 1 segments to the depth + 1 the path has (max_depth, Mitsuba's
    // meaning); BSDF sampling cannot produce longer paths, so neither may MNEE.
    query.max_k = m_path->max_depth >= 0 ? m_path->max_depth - m_walk.depth - 2 : -1;
    query.directions = &m_walk.directions();
    return query;
}

double reflected_connection_weight(const ReflectedConnection& r) {
    return power_heuristic(r.density, {r.pdf_bsdf, r.pdf_nee});
}

void MneePath::connect_reflected(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx,
                                 Sampler& sampler) {
    const ReflectedConnection r = m_reflection.connect(query_at(si, bsdf, sctx), sampler);
    if (!r.found) return;
    // BSDF sampling's copies of the path keep their MIS weight in the biased mode too
    // (emitter_weight drops no path the connection can produce).
    m_out.add(Technique::MneeReflected, m_walk.tp.beta * r.value * reflected_connection_weight(r));
}

SampledSpectrum MneePath::connect_at_interface(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx,
                                               Sampler& sampler) {
    const Scene& scene = *m_scene;
    const RefractiveSuffix& s = m_suffix;
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, si, m_ctx.wl, sampler, &light, &pmf);
    if (!ls) return {};
    // NEE from a rough y after x_b may make the reflected connection's path (x_b, y, x_c with y
    // reflecting off the outside of glass).
    const bool refracts = dot(si.wo, si.ng) * dot(ls->wi, si.ng) < 0;
    const bool reflected = m_reflects && s.has_xb && s.k == 1 && !refracts;
    if (!s.has_xb || s.k == 0 || !(m_weighs_mnee || reflected))
        return nee_connect(scene, si, bsdf, sctx, m_walk.media, *ls, pmf, m_walk.directions());
    const Vec3 wo = si.to_local(si.wo), wi = si.to_local(ls->wi);
    const SampledSpectrum f = bsdf.eval(sctx, wo, wi);
    if (f.is_zero()) return {};
    if (!light_visible(scene, si, *ls)) return {};
    // The path x_b, x_1..x_k = si, x_c in area measure (lights at infinity on MNEE's far sphere).
    const LightPoint lp = light_point_hit(scene, *light, ls->p, ls->n, ls->uv, ls->wi, s.xb.p);
    const double p_nee = s.p_prefix * pmf * light_point_pdf(scene, *light, si.p, lp.p, lp.n);
    const double p_bsdf =
        lp.delta ? 0.0
                 : s.p_prefix * bsdf.pdf(sctx, wo, wi) * std::abs(dot(lp.n, ls->wi)) / length_squared(lp.p - si.p);
    const double q = connect_probability(*light);
    DensityDetail detail;
    bool cut = false;
    const double p_m = mnee_density(refracts, *light, pmf, lp.p, lp.n, q, p_nee + p_bsdf, &detail, &cut);
    const double p_mnee = cut ? 0.0 : q * p_m;
    const double p_r = reflected ? m_reflection.density(s.xb, *s.xb.bsdf(), s.xb_media, s.chain[0], *light, pmf, lp.p,
                                                        lp.n, m_ctx.hero(), p_nee + p_bsdf + p_mnee)
                                 : 0.0;
    if (m_mnee->biased && covers(refracts) && !(p_mnee > 0) && !(p_r > 0)) return {};
    const SampledSpectrum unweighted = nee_estimate(si, bsdf, sctx, m_walk.media, *ls, f, pmf, 1.0);
    if (m_pilot && !light->is_delta())
        record_other((m_walk.tp.beta * unweighted).average(), p_nee, p_m, detail, p_nee + p_bsdf, q);
    return unweighted * power_heuristic(p_nee, {p_bsdf, p_mnee, p_r});
}

double MneePath::emitter_weight(const Light& light, const Vec3& p, const Vec3& n, const Vec3& d,
                                const SampledSpectrum& value) const {
    const Scene& scene = *m_scene;
    const RefractiveSuffix& s = m_suffix;
    // One reflection off the outside of glass: the reflected connection's path too.
    const bool reflected = m_reflects && s.k == 1 && !s.transmissions_only;
    if (!s.has_xb || s.k == 0 || !(m_weighs_mnee || reflected)) return m_prev.emitter_weight(scene, light, p, n, d);
    // A BSDF-sampled path x_b, x_1..x_k (refractive), x_c: three techniques can produce it.
    const LightPoint lp = light_point_hit(scene, light, p, n, Vec2(), d, s.xb.p);  // densities only: no uv
    const double pmf = scene.light_sampler().pmf(&light);
    const size_t last = size_t(s.k - 1);
    const double p_bsdf = s.p_prefix * s.q_last * std::abs(dot(lp.n, d)) / length_squared(lp.p - s.chain[last].p);
    const double q = connect_probability(light);
    const double p_nee =
        s.specular[last] ? 0.0 : s.p_prefix * pmf * light_point_pdf(scene, light, s.chain[last].p, lp.p, lp.n);
    DensityDetail detail;
    bool cut = false;
    const double p_m = mnee_density(true, light, pmf, lp.p, lp.n, q, p_bsdf + p_nee, &detail, &cut);
    const double p_mnee = cut ? 0.0 : q * p_m;
    if (m_pilot) record_other(value.average(), p_bsdf, p_m, detail, p_bsdf + p_nee, q);
    const double p_r = reflected ? m_reflection.density(s.xb, *s.xb.bsdf(), s.xb_media, s.chain[0], light, pmf, lp.p,
                                                        lp.n, m_ctx.hero(), p_bsdf + p_nee + p_mnee)
                                 : 0.0;
    // Sec. 3.5's outlier removal: light that BSDF sampling finds on a path of MNEE's class (a
    // transmissive suffix; any suffix with reflections=true) where no MNEE technique can produce
    // it is dropped. A suffix with a reflection is outside that class by default, as in the paper:
    // dropping it too lost the bunny's internal reflections, 3.5 % of its caustic, which the
    // outlier clamp keeps without their fireflies (docs/experiments.md, twenty-fifth measurement).
    if (m_mnee->biased && covers(true) && !(p_mnee > 0) && !(p_r > 0)) return 0.0;
    return power_heuristic(p_bsdf, {p_mnee, p_nee, p_r});
}

Technique MneePath::emitter_technique() const {
    if (!m_suffix.has_xb || m_suffix.k == 0) return Technique::BsdfHit;
    return m_suffix.transmissions_only ? Technique::BsdfRefracted : Technique::BsdfReflected;
}

void MneePath::arrive(const SurfaceInteraction& si) {
    RefractiveSuffix& s = m_suffix;
    if (!s.has_xb || !is_manifold_interface(si.bsdf(), m_ctx.hero())) return;
    if (s.k >= RefractiveSuffix::kMaxVertices) {
        s.has_xb = false;
        return;
    }
    // Where no MIS weight reads MNEE's density, only the reflected connection's class (x_b and
    // one vertex) needs the suffix.
    if (!m_weighs_mnee && !(m_reflects && s.k == 0)) {
        ++s.k;
        return;
    }
    // Area density of reaching this vertex: solid-angle density times |cos| / d^2.
    s.p_prefix *= s.q_last * std::abs(dot(si.ng, m_walk.ray.d)) / (si.t * si.t);
    s.chain.set(size_t(s.k++), si);
}

void MneePath::scattered(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                         const MediumStack& media_before) {
    RefractiveSuffix& s = m_suffix;
    if (is_manifold_interface(&bsdf, m_ctx.hero())) {
        if (!s.has_xb) return;
        const size_t i = size_t(s.k - 1);
        s.specular[i] = bs.is_delta();
        if (!(bs.lobe & kTransmission)) s.transmissions_only = false;
        if (!m_weighs_mnee && !(m_reflects && s.k == 1)) return;
        const ManifoldVertex v = ManifoldVertex::from_interaction(si, bsdf.eta(m_ctx.hero()));
        s.q_last = vertex_bsdf_density(v, si.wo, bs.wi, m_ctx.at(si));
    } else if (bsdf.is_smooth_sampled() && !bs.is_delta()) {
        // A new x_b: MNEE connected from here.
        if (m_weighs_mnee || m_reflects)
            s.start(si, media_before, bs.pdf);
        else
            s.restart();
    } else {
        s.has_xb = false;
    }
}

double MneePath::mnee_density(bool last_refracts, const Light& light, double pmf, const Vec3& p, const Vec3& n,
                              double q, double p_others, DensityDetail* detail, bool* cut) const {
    *detail = DensityDetail();
    detail->want_probe = m_pilot != nullptr;
    *cut = false;
    const RefractiveSuffix& s = m_suffix;
    // q = 0: the region leaves these paths to BSDF sampling, and MIS needs no density (nor its walk).
    if (!covers(last_refracts) || !(q > 0)) return 0.0;
    // Where the others' density dwarfs the most MNEE's can be, MNEE has no share (mis_cutoff),
    // and Alg. 2's walk is not needed, but by the pilot's record: its model weighs every
    // candidate q as without the cutoff, which moves those weights by under 1 / (1 + K^2).
    *cut = m_mnee->mis_cutoff > 0 &&
           mis_cut_off(p_others,
                       q * solution_density_bound(*m_scene, *m_mnee, s.xb, *s.xb.bsdf(), s.chain.data(), s.k, light,
                                                  pmf, p, n, m_ctx.hero()),
                       m_mnee->mis_cutoff);
    if (*cut) {
        ++walk_counters::mis_cut_densities;
        if (!m_pilot) return 0.0;
    }
    const double w0 = m_pilot ? work_so_far() : 0.0;
    const double d = m_technique.density(s.xb, *s.xb.bsdf(), s.chain.data(), s.k, light, pmf, p, n, m_ctx.hero(),
                                         m_surface_trials, detail, m_failed_walk_trials);
    // A cut density's work is charged as if it ran, so that the allocation chooses as without
    // the cutoff: charged only at the pilot's q, the walks looked cheap at small q, and the balls
    // on a plane walked in more regions, where walks do not pay (docs/mnee.md, "The MIS cutoff").
    if (m_pilot) m_pilot->work_density += work_so_far() - w0;
    return d;
}

void MneePath::record_other(double value, double p_t, double p_m, const DensityDetail& detail, double p_other,
                            double q) const {
    if (p_m > 0)
        m_pilot->add_other(value, p_t, p_m, detail.weight, p_other, q, detail.surface_path);
    else if (detail.probe > 0)
        m_pilot->add_probe_other(value, p_t, detail.probe, p_other, q);
}

bool MneePath::cut_off(const ManifoldSolution& sol, double q) const {
    // The same test, on the same numbers, as the 1 / p estimate's (count_trials_to_refind).
    return mis_cut_off(sol.pdf_bsdf + sol.pdf_nee_last, q * sol.bound, m_mnee->mis_cutoff);
}

double MneePath::connect_probability(const Light& light) const {
    if (light.is_delta()) return 1.0;
    return m_q >= 0 ? m_q : m_mnee->connect_probability;
}

bool MneePath::covers(bool last_refracts) const {
    if (m_mnee->reflections && m_mnee->solutions != MneeSolutions::One) return true;
    return m_suffix.transmissions_only && last_refracts;
}

}  // namespace snell
