#include "manifold/mnee.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bsdf/microfacet.h"
#include "manifold/exterior_reflection.h"
#include "manifold/generalized_geometry.h"
#include "manifold/half_vectors.h"
#include "manifold/manifold_walk.h"
#include "manifold/seed_path.h"
#include "manifold/solution_set.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

namespace {

namespace wc = walk_counters;

bool is_specular(const ManifoldVertex& v) { return !v.bsdf->has_microfacet(); }

/// IOR of the side of v that direction w points into (1 outside, eta inside).
double side_ior(const ManifoldVertex& v, const Vec3& w) { return dot(w, v.ng) >= 0 ? 1.0 : v.eta; }

/// Directions (towards the camera side, towards the light side) at vertex i of a chain.
void vertex_directions(const Vec3& xb, const std::vector<ManifoldVertex>& chain, const Vec3& xc, size_t i, Vec3* wi,
                       Vec3* wo) {
    *wi = normalize((i == 0 ? xb : chain[i - 1].p) - chain[i].p);
    *wo = normalize((i + 1 == chain.size() ? xc : chain[i + 1].p) - chain[i].p);
}

/// The path's vertices x_1..x_k as manifold vertices at wavelength `lambda`; false where one is
/// not a manifold interface.
bool manifold_vertices_of(const SurfaceInteraction* path, int k, double lambda, std::vector<ManifoldVertex>* chain) {
    chain->assign(size_t(std::max(k, 0)), ManifoldVertex{});
    for (int i = 0; i < k; ++i) {
        const BSDF* b = path[i].bsdf();
        if (!is_manifold_interface(b, lambda)) return false;
        (*chain)[size_t(i)] = ManifoldVertex::from_interaction(path[i], b->eta(lambda));
    }
    return true;
}

/// Each vertex scatters as the path does there: reflects where both its directions lie on one side.
void scatter_as_the_path(const Vec3& xb, std::vector<ManifoldVertex>& chain, const Vec3& xc) {
    for (size_t i = 0; i < chain.size(); ++i) {
        Vec3 wi, wo;
        vertex_directions(xb, chain, xc, i, &wi, &wo);
        chain[i].reflect = dot(wi, chain[i].ng) * dot(wo, chain[i].ng) > 0;
    }
}

wc::WalkEnd walk_end_of(WalkOutcome o) {
    switch (o) {
        case WalkOutcome::Converged:
            return wc::WalkEnd::Found;
        case WalkOutcome::MaxIterations:
            return wc::WalkEnd::MaxIterations;
        case WalkOutcome::Stalled:
            return wc::WalkEnd::Stalled;
        case WalkOutcome::SingularMatrix:
            return wc::WalkEnd::Singular;
        case WalkOutcome::ProjectionFailed:
            return wc::WalkEnd::ProjectionFailed;
    }
    return wc::WalkEnd::Singular;
}

uint64_t elapsed_ns(std::chrono::steady_clock::time_point t0) {
    return uint64_t(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace

/// Each vertex refracts, and for rough ones both directions see the microfacet from their
/// own side (otherwise the converged path is not one the BSDF can scatter).
bool chain_admissible(const Vec3& xb, const std::vector<ManifoldVertex>& chain, const Vec3& xc) {
    for (size_t i = 0; i < chain.size(); ++i) {
        const ManifoldVertex& v = chain[i];
        const Vec3 wi = normalize((i == 0 ? xb : chain[i - 1].p) - v.p);
        const Vec3 wo = normalize((i + 1 == chain.size() ? xc : chain[i + 1].p) - v.p);
        // The scattering the chain asks of the vertex: wi and wo on one side (reflect) or not.
        if ((dot(wi, v.ng) * dot(wo, v.ng) > 0) != v.reflect) return false;
        const Vec3 h = generalized_half_vector(v, wi, wo);
        if (!(dot(wi, h) * dot(wi, v.ng) > 0) || !(dot(wo, h) * dot(wo, v.ng) > 0)) return false;
    }
    return true;
}

double half_vector_jacobian(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo, const Vec3& h) {
    const double eta_i = side_ior(v, wi), eta_o = side_ior(v, wo);
    if (eta_i == eta_o) return 4.0 * std::abs(dot(wo, h));  // reflection (Eq. 14)
    const double wo_h = std::abs(dot(wo, h));
    if (!(wo_h > 0)) return 0;
    return sqr(eta_i * dot(wi, h) + eta_o * dot(wo, h)) / (eta_o * eta_o * wo_h);  // refraction (Eq. 16)
}

double half_vector_density(const ManifoldVertex& v, const Vec3& h) {
    if (is_specular(v)) return 1.0;
    const Vec3 hl = v.si.to_local(h);
    // D where the vertex lies (a roughness texture is read at the converged point).
    return hl.z > 0 ? v.bsdf->microfacet(BSDFContext{}.at(v.si))->D(hl) : 0.0;
}

SampledSpectrum vertex_measurement(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo,
                                   const BSDFContext& path_ctx) {
    const BSDFContext ctx = path_ctx.at(v.si);
    const Vec3 wi_l = v.si.to_local(wi), wo_l = v.si.to_local(wo);
    // BSDF convention: its wo is our camera-side wi, its wi our light-side wo.
    if (is_specular(v)) return v.bsdf->eval_delta(ctx, wi_l, wo_l);  // Eq. 9: kappa
    const Vec3 h = generalized_half_vector(v, wi, wo);
    const double cos_h = std::abs(dot(h, v.n));
    if (!(cos_h > 0)) return {};
    // Eq. 6: f_r |do/dh| |<o, n>| / |<h, n>|.
    return v.bsdf->eval(ctx, wi_l, wo_l) * (std::abs(wo_l.z) * half_vector_jacobian(v, wi, wo, h) / cos_h);
}

double vertex_bsdf_density(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo, const BSDFContext& path_ctx) {
    const BSDFContext ctx = path_ctx.at(v.si);
    const Vec3 wi_l = v.si.to_local(wi), wo_l = v.si.to_local(wo);
    if (!is_specular(v)) return v.bsdf->pdf(ctx, wi_l, wo_l);
    // A delta lobe: its discrete probability, with delta(o) rewritten as delta(h) / |do/dh|.
    const double J = half_vector_jacobian(v, wi, wo, generalized_half_vector(v, wi, wo));
    return J > 0 ? v.bsdf->pdf_delta(ctx, wi_l, wo_l) / J : 0.0;
}

TangentBasis light_point_basis(const Vec3& p, const Vec3& n, const Vec3& arrival_dir) {
    const Frame f = Frame::from_normal(length_squared(n) > 0 ? n : arrival_dir);
    return {p, f.s, f.t};
}

bool mnee_seed_culled(const SurfaceInteraction& xb, const BSDF& bsdf_b, const Vec3& xc, double margin) {
    if (bsdf_b.is_transmissive()) return false;
    const Vec3 n = dot(xb.wo, xb.n) >= 0 ? xb.n : -xb.n;  // the side the path arrived on
    return dot(n, normalize(xc - xb.p)) < -margin;
}

MneeConnection mnee_connect(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb,
                            const BSDF& bsdf_b, const BSDFContext& ctx, const MediumStack& media, const Light& light,
                            double pmf, const LightPoint& lp, std::vector<ManifoldVertex>& chain, Sampler& sampler) {
    HalfVectorDraws draws(sampler);
    return mnee_connect(scene, st, xb, bsdf_b, ctx, media, light, pmf, lp, chain, draws);
}

MneeOutcome mnee_walk(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb, const BSDF& bsdf_b,
                      const LightPoint& lp, std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws,
                      bool trial_only) {
    if (mnee_seed_culled(xb, bsdf_b, lp.p, st.cull_margin)) {
        ++wc::seeds_culled;
        return MneeOutcome::SeedCulled;
    }
    // Sec. 3.2 then Sec. 3.4: half vectors, then the walk from the seed.
    set_half_vectors(chain, draws);
    ++wc::walks_started;
    const auto t0 = std::chrono::steady_clock::now();
    const TangentBasis seed_basis = light_point_basis(lp.p, lp.n, normalize(lp.p - xb.p));
    const WalkResult walk = manifold_walk(&scene, xb.p, chain, seed_basis, st.walk);
    wc::walk_time.add_ns(elapsed_ns(t0));
    switch (walk.outcome) {
        case WalkOutcome::Converged:
            break;
        case WalkOutcome::MaxIterations:
            ++wc::walk_fail_no_convergence;
            wc::count_walk_end(false, wc::WalkEnd::MaxIterations);
            return MneeOutcome::NoConvergence;
        case WalkOutcome::Stalled:
            ++wc::walk_fail_no_convergence;
            wc::count_walk_end(false, wc::WalkEnd::Stalled);
            return MneeOutcome::Stalled;
        case WalkOutcome::SingularMatrix:
            ++wc::walk_fail_singular;
            wc::count_walk_end(false, wc::WalkEnd::Singular);
            return MneeOutcome::Singular;
        case WalkOutcome::ProjectionFailed:
            ++wc::walk_fail_projection;
            wc::count_walk_end(false, wc::WalkEnd::ProjectionFailed);
            return MneeOutcome::ProjectionFailed;
    }
    if (!chain_admissible(xb.p, chain, lp.p)) {
        ++wc::walk_fail_scattering;
        wc::count_walk_end(false, wc::WalkEnd::WrongScattering);
        return MneeOutcome::WrongScattering;
    }
    ++wc::walks_converged;
    wc::walk_iterations_success += uint64_t(walk.iterations);
    wc::iteration_histogram.add(walk.iterations);
    if (trial_only) wc::count_walk_end(false, wc::WalkEnd::Found);
    return MneeOutcome::Success;
}

MneeConnection mnee_connect(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb,
                            const BSDF& bsdf_b, const BSDFContext& ctx, const MediumStack& media, const Light& light,
                            double pmf, const LightPoint& lp, std::vector<ManifoldVertex>& chain,
                            HalfVectorDraws& draws) {
    MneeConnection out;
    out.outcome = mnee_walk(scene, st, xb, bsdf_b, lp, chain, draws);
    out.walk_converged = out.outcome == MneeOutcome::Success || out.outcome == MneeOutcome::WrongScattering;
    if (out.outcome != MneeOutcome::Success) return out;
    const Vec3 xc = lp.p;

    // Self-occlusion was ignored for the seed; the admissible path must be visible (Sec. 3.1).
    const size_t k = chain.size();
    bool visible = !scene.occluded(scene.spawn_ray_to(xb, chain[0].si));
    for (size_t i = 0; i < k && visible; ++i)
        visible = !scene.occluded(i + 1 < k ? scene.spawn_ray_to(chain[i].si, chain[i + 1].si)
                                            : scene.spawn_ray_to(chain[i].si, xc, lp.p_error));
    if (!visible) {
        ++wc::walk_fail_occluded;
        wc::count_walk_end(false, wc::WalkEnd::Occluded);
        out.outcome = MneeOutcome::Occluded;
        return out;
    }

    // Measurement in half-vector space (Eq. 6): f_r(x_b) |cos| |do_b/dx_c| prod(vertex) Le.
    const Vec3 o_b = normalize(chain[0].p - xb.p);
    const Vec3 wo_b = xb.to_local(xb.wo), o_b_l = xb.to_local(o_b);
    const SampledSpectrum f_b = bsdf_b.eval(ctx.at(xb), wo_b, o_b_l) * std::abs(o_b_l.z);
    const Vec3 from_light = normalize(chain[k - 1].p - xc);
    const SampledSpectrum Le = light_point_emission(light, lp, from_light, xb.p, ctx.wl);
    if (f_b.is_zero() || Le.is_zero()) {
        wc::count_walk_end(false, wc::WalkEnd::Zero);
        out.outcome = MneeOutcome::Zero;
        return out;
    }
    const ChainJacobians jac = chain_jacobians(xb.p, chain, light_point_basis(xc, lp.n, -from_light));
    if (!jac.valid) {
        ++wc::walk_fail_singular;
        wc::count_walk_end(false, wc::WalkEnd::Singular);
        out.outcome = MneeOutcome::Singular;
        return out;
    }
    SampledSpectrum f_dH(1.0);  // the chain's measurement in half-vector space (Eq. 6)
    double p_dH = 1;            // p_dH(H): the density of the half vectors drawn (Sec. 3.2)
    MediumStack m = media;
    SampledSpectrum tr = m.transmittance(length(chain[0].p - xb.p), ctx.wl);
    // BSDF-sampling density of the same path (area measure), and its prefix up to x_k.
    out.pdf_xb_direction = bsdf_b.pdf(ctx.at(xb), wo_b, o_b_l);
    double p_bsdf = out.pdf_xb_direction * std::abs(dot(chain[0].ng, o_b)) / length_squared(chain[0].p - xb.p);
    double p_prefix_k = p_bsdf;
    for (size_t i = 0; i < k; ++i) {
        Vec3 wi, wo;
        vertex_directions(xb.p, chain, xc, i, &wi, &wo);
        const ManifoldVertex& v = chain[i];
        f_dH *= vertex_measurement(v, wi, wo, ctx);
        // The chain was solved for the hero's eta: with dispersion it is the hero's path alone.
        out.hero_only = out.hero_only || v.bsdf->dispersive();
        p_dH *= half_vector_density(v, generalized_half_vector(v, wi, wo));
        // Beer-Lambert inside absorbing interiors along the admissible path.
        if (!v.reflect) m.cross(v.bsdf->interior_absorption(), dot(wi, v.ng) > 0);
        const Vec3 next = i + 1 < k ? chain[i + 1].p : xc;
        tr *= m.transmittance(length(next - v.p), ctx.wl);
        const Vec3 next_n = i + 1 < k ? chain[i + 1].ng : lp.n;
        p_prefix_k = p_bsdf;
        p_bsdf *= vertex_bsdf_density(v, wi, wo, ctx) * std::abs(dot(next_n, wo)) / length_squared(next - v.p);
    }
    const double p_point = lp.pdf;
    if (f_dH.is_zero() || !(p_dH > 0) || !(p_point > 0)) {
        wc::count_walk_end(false, wc::WalkEnd::Zero);
        out.outcome = MneeOutcome::Zero;
        return out;
    }
    wc::count_walk_end(false, wc::WalkEnd::Found);
    out.outcome = MneeOutcome::Success;
    // Alg. 1, last line: f_r(x_b) f_dH(X) L_e(x_c) / (p_dH(H) p_dx(x_c)), with the light's pmf in
    // p_dx; |do_b/dx_c| turns x_b's projected solid angle into x_c's area.
    out.value = f_b * f_dH * Le * tr * (jac.do_b_dx_c / (p_dH * pmf * p_point));
    // The generalised geometry term over the free-space one (dimensionless, scale-free); the
    // optional clamp of its fold tail.
    const double cos_c = length_squared(lp.n) > 0 ? std::abs(dot(lp.n, from_light)) : 1.0;
    out.focusing = jac.do_b_dx_c * length_squared(xc - xb.p) / std::max(cos_c, 1e-12);
    if (st.max_geometry > 0 && out.focusing > st.max_geometry) {
        out.value *= st.max_geometry / out.focusing;
        ++wc::geometry_clamped;
    }
    out.pdf_mnee = pmf * p_point * p_dH * jac.dH_dX;  // Eq. 7 with Eq. 8
    // Delta lights cannot be hit by BSDF sampling.
    out.pdf_bsdf = lp.delta ? 0.0 : p_bsdf;
    // NEE from a rough last vertex competes for the same path.
    if (!is_specular(chain[k - 1]))
        out.pdf_nee_last = p_prefix_k * pmf * light_point_pdf(scene, light, chain[k - 1].p, xc, lp.n);
    return out;
}

bool chain_of_path(const SurfaceInteraction& xb, const SurfaceInteraction* path, int k, const Vec3& xc, double lambda,
                   std::vector<ManifoldVertex>* chain, std::vector<Vec2>* unit_slopes) {
    unit_slopes->assign(size_t(std::max(k, 0)), Vec2(0, 0));
    if (!manifold_vertices_of(path, k, lambda, chain)) return false;
    scatter_as_the_path(xb.p, *chain, xc);
    for (size_t i = 0; i < chain->size(); ++i) {
        ManifoldVertex& v = (*chain)[i];
        if (is_specular(v)) continue;
        Vec3 wi, wo;
        vertex_directions(xb.p, *chain, xc, i, &wi, &wo);
        v.h_target = tangential(v, generalized_half_vector(v, wi, wo));
        (*unit_slopes)[i] = unit_slope_of(v, v.h_target);
    }
    return true;
}

StraightSeed trace_straight_seed(const Scene& scene, const SurfaceInteraction& xb, const Vec3& xc, double lambda,
                                 const MneeSettings& settings) {
    StraightSeed s;
    s.status = trace_seed_path(scene, xb, xc, lambda, settings, &s.chain);
    return s;
}

namespace {
// Alg. 2 lines 1, 3 and 8 for the path as it scatters; `reflects`: whether it reflects anywhere.
double chain_solution_density(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb,
                              const BSDF& bsdf_b, const SurfaceInteraction* path, int k, const Light& light, double pmf,
                              const Vec3& xc, const Vec3& nc, double lambda, bool* reflects) {
    *reflects = false;
    if (k <= 0 || k > st.max_vertices) return 0;
    const double p_point = light_point_pdf(scene, light, xb.p, xc, nc);  // line 1
    if (!(p_point > 0) || mnee_seed_culled(xb, bsdf_b, xc, st.cull_margin)) return 0;
    std::vector<ManifoldVertex> input;
    if (!manifold_vertices_of(path, k, lambda, &input)) return 0;
    scatter_as_the_path(xb.p, input, xc);  // each vertex as the path itself scatters there
    for (const ManifoldVertex& v : input) *reflects = *reflects || v.reflect;
    if (!chain_admissible(xb.p, input, xc)) return 0;
    double p_dH = 1;  // line 3, on the path's own half vectors
    for (int i = 0; i < k; ++i) {
        Vec3 wi, wo;
        vertex_directions(xb.p, input, xc, size_t(i), &wi, &wo);
        p_dH *= half_vector_density(input[size_t(i)], generalized_half_vector(input[size_t(i)], wi, wo));
    }
    if (!(p_dH > 0)) return 0;
    const ChainJacobians jac = chain_jacobians(xb.p, input, light_point_basis(xc, nc, normalize(xc - xb.p)));
    return jac.valid ? pmf * p_point * p_dH * jac.dH_dX : 0.0;  // line 8
}
}  // namespace

double solution_density_bound(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb,
                              const BSDF& bsdf_b, const SurfaceInteraction* path, int k, const Light& light, double pmf,
                              const Vec3& xc, const Vec3& nc, double lambda) {
    bool reflects = false;
    return chain_solution_density(scene, st, xb, bsdf_b, path, k, light, pmf, xc, nc, lambda, &reflects);
}

double solution_density(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb, const BSDF& bsdf_b,
                        const SurfaceInteraction* path, int k, const Light& light, double pmf, const Vec3& xc,
                        const Vec3& nc, double lambda, const StraightSeed* traced) {
    for (int i = 0; i < k; ++i)
        if (path[i].emitter()) return 0;
    bool reflects = false;
    const double p = chain_solution_density(scene, st, xb, bsdf_b, path, k, light, pmf, xc, nc, lambda, &reflects);
    if (!(p > 0) || (reflects && !st.reflections)) return 0;  // reflections only with settings.reflections
    // One reflection off the outside of glass is ExteriorReflection's path, where it runs.
    if (reflects && k == 1 && st.exterior_reflections > 0 && ExteriorReflection::in_class(xb.p, path[0], xc, lambda))
        return 0;
    // The domain: refractive interfaces lie on the straight segment x_b -> x_c, blocked by an
    // opaque surface or not (the integrator runs the surface seeds for both).
    const SeedStatus status = traced ? traced->status : trace_straight_seed(scene, xb, xc, lambda, st).status;
    return status == SeedStatus::Refractive || status == SeedStatus::Blocked ? p : 0.0;
}

double mnee_pdf(const Scene& scene, const MneeSettings& st, const SurfaceInteraction& xb, const BSDF& bsdf_b,
                const SurfaceInteraction* path, int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                double lambda, const StraightSeed* traced, bool* walk_converged) {
    if (walk_converged) *walk_converged = false;
    if (k <= 0 || k > st.max_vertices) return 0;
    // Alg. 2, line 1: density of x_c as the light sampler would produce it from x_b.
    const double p_point = light_point_pdf(scene, light, xb.p, xc, nc);
    if (!(p_point > 0) || mnee_seed_culled(xb, bsdf_b, xc, st.cull_margin)) return 0;

    // The input path as manifold vertices, with its own half vectors.
    std::vector<ManifoldVertex> input;
    if (!manifold_vertices_of(path, k, lambda, &input)) return 0;
    if (!chain_admissible(xb.p, input, xc)) return 0;

    // Line 2: the seed path from x_b to x_c must cross the same shapes in the same order.
    StraightSeed own;
    if (!traced) own = trace_straight_seed(scene, xb, xc, lambda, st);
    if ((traced ? traced : &own)->status != SeedStatus::Refractive) return 0;
    std::vector<ManifoldVertex> seed = traced ? traced->chain : std::move(own.chain);  // the walk moves it
    if (int(seed.size()) != k) return 0;
    double p_dH = 1;
    for (int i = 0; i < k; ++i) {
        if (seed[size_t(i)].shape != input[size_t(i)].shape) return 0;
        Vec3 wi, wo;
        vertex_directions(xb.p, input, xc, size_t(i), &wi, &wo);
        const Vec3 h = generalized_half_vector(input[size_t(i)], wi, wo);
        // Line 3: p_dH on the input path's half vectors (consistent MIS weights).
        p_dH *= half_vector_density(input[size_t(i)], h);
        input[size_t(i)].h_target = is_specular(input[size_t(i)]) ? Vec2(0, 0) : tangential(input[size_t(i)], h);
        // The walk re-reads the target as the estimator's does: the unit slope that gives h at
        // the input vertex, stretched by the roughness wherever the walk goes.
        seed[size_t(i)].has_unit_slope = !is_specular(input[size_t(i)]);
        if (seed[size_t(i)].has_unit_slope)
            seed[size_t(i)].unit_slope = unit_slope_of(input[size_t(i)], input[size_t(i)].h_target);
        seed[size_t(i)].h_target = seed[size_t(i)].has_unit_slope
                                       ? target_from_unit_slope(seed[size_t(i)], seed[size_t(i)].unit_slope)
                                       : input[size_t(i)].h_target;
    }
    if (!(p_dH > 0)) return 0;

    // Line 4: walk from the seed with those half vectors.
    ++wc::pdf_walks;
    const TangentBasis basis = light_point_basis(xc, nc, normalize(xc - xb.p));
    const auto t0 = std::chrono::steady_clock::now();
    const WalkResult walk = manifold_walk(&scene, xb.p, seed, basis, st.walk);
    wc::walk_time.add_ns(elapsed_ns(t0));
    if (walk.outcome != WalkOutcome::Converged) {
        wc::count_walk_end(true, walk_end_of(walk.outcome));
        return 0;
    }
    if (walk_converged) *walk_converged = true;
    // Lines 5-7: a different admissible path means MNEE cannot produce the input one.
    std::vector<ManifoldVertex> target = input;
    polish_solution(&scene, xb.p, seed, basis, st.walk);
    polish_solution(&scene, xb.p, target, basis, st.walk);
    if (!same_solution(xb.p, seed, target, xc)) {
        wc::count_walk_end(true, wc::WalkEnd::OtherSolution);
        return 0;
    }
    ++wc::pdf_walks_found;
    // Line 8: p_dX = p_dH |dH/dX| (Eq. 7, 8), times the light point's density.
    const ChainJacobians jac = chain_jacobians(xb.p, input, basis);
    if (!jac.valid) {
        wc::count_walk_end(true, wc::WalkEnd::Singular);
        return 0;
    }
    wc::count_walk_end(true, wc::WalkEnd::Found);
    return pmf * p_point * p_dH * jac.dH_dX;
}

}  // namespace snell
