#include "manifold/exterior_reflection.h"

#include <algorithm>
#include <cmath>

#include "bsdf/bsdf.h"
#include "geometry/shape.h"
#include "light/light.h"
#include "manifold/caster_choice.h"
#include "manifold/half_vectors.h"
#include "manifold/light_point.h"
#include "manifold/mis_cutoff.h"
#include "manifold/mnee.h"
#include "manifold/seed_path.h"
#include "manifold/solution_set.h"
#include "scene/caster_sampling.h"
#include "scene/light_choice.h"
#include "scene/scene.h"

namespace snell {

namespace {

// The bounding sphere the scene keeps for a caster (Scene::manifold_caster_bounds).
const BoundingSphere* bounds_of(const Scene& scene, const Shape& caster) {
    const std::vector<const Shape*>& all = scene.manifold_casters();
    for (size_t i = 0; i < all.size(); ++i)
        if (all[i] == &caster) return &scene.manifold_caster_bounds()[i];
    return nullptr;
}

// The point of sphere b where a mirror reflects x_b to x_c (both outside it; Alhazen's problem).
// Its normal lies on the great arc from a, the direction of x_b seen from the centre, to c, that of
// x_c, where the two directions make equal angles with it: the difference g of those cosines runs
// from positive (the point facing x_b) to negative (facing x_c) along the arc. The arc is
// parametrised by normalize(a + t (c - a)), t in [0, 1] (no trigonometry), and g's zero found by
// regula falsi (the Illinois variant) to far below the walk's tolerance in a few evaluations; the
// walk polishes what is left.
bool sphere_mirror_point(const BoundingSphere& b, const Vec3& xb, const Vec3& xc, Vec3* out) {
    const Vec3 to_b = xb - b.center, to_c = xc - b.center;
    const double r2 = b.radius * b.radius;
    if (!(length_squared(to_b) > r2) || !(length_squared(to_c) > r2)) return false;
    const Vec3 a = normalize(to_b), c = normalize(to_c);
    if (!(dot(a, c) > -1 + 1e-9)) return false;  // x_b and x_c opposite: the mirror point is any rim point
    const auto normal_at = [&](double t) { return normalize(a + (c - a) * t); };
    const auto g = [&](double t) {
        const Vec3 n = normal_at(t), p = b.center + n * b.radius;
        return dot(n, normalize(xb - p)) - dot(n, normalize(xc - p));
    };
    double t0 = 0, t1 = 1, g0 = g(0), g1 = g(1), t = 0.5;
    int side = 0;
    for (int i = 0; i < 32 && g0 > 0 && g1 < 0; ++i) {
        t = (t0 * g1 - t1 * g0) / (g1 - g0);
        const double gt = g(t);
        if (std::abs(gt) < 1e-12) break;
        if (gt > 0) {
            t0 = t, g0 = gt;
            if (side == 1) g1 *= 0.5;  // Illinois: the end kept twice in a row weighs half
            side = 1;
        } else {
            t1 = t, g1 = gt;
            if (side == -1) g0 *= 0.5;
            side = -1;
        }
        if (t1 - t0 < 1e-12) break;
    }
    *out = b.center + normal_at(t) * b.radius;
    return true;
}

}  // namespace

bool ExteriorReflection::in_class(const Vec3& xb, const SurfaceInteraction& y, const Vec3& xc, double lambda) {
    return y.shape && !y.emitter() && is_manifold_interface(y.bsdf(), lambda) && dot(xb - y.p, y.ng) > 0 &&
           dot(xc - y.p, y.ng) > 0;
}

bool ExteriorReflection::made(const Scene& scene, const MneeSettings& settings) {
    return settings.exterior_reflections > 0 && !scene.manifold_casters().empty();
}

bool ExteriorReflection::seed(const Shape& caster, const SurfaceInteraction& xb, const BSDF& bsdf_b, const Vec3& xc,
                              double lambda, ManifoldVertex* v) const {
    const BoundingSphere* b = bounds_of(*m_scene, caster);
    if (!b || !(b->radius > 0)) return false;
    // The mirror point of the caster's bounding sphere: the caster's own where it is a sphere, and
    // close to it on any convex caster, so the walk has little left to move.
    Vec3 m;
    if (!sphere_mirror_point(*b, xb.p, xc, &m)) return false;
    SurfaceInteraction si;
    if (!caster.closest_point(m, 2 * b->radius, &si)) return false;
    si.wo = normalize(xb.p - si.p);
    if (!is_manifold_interface(si.bsdf(), lambda)) return false;
    // A seed that faces away from x_b or x_c (a caster unlike its bounding sphere) starts walks
    // that mostly fail at full cost.
    if (!(dot(xb.p - si.p, si.ng) > 0) || !(dot(xc - si.p, si.ng) > 0)) return false;
    // A reflecting x_b scatters into its own side alone (a floor does not light what lies below
    // it); the walk rarely crosses that horizon.
    if (!bsdf_b.is_transmissive() && !(dot(si.p - xb.p, xb.ng) * dot(xb.wo, xb.ng) > 0)) return false;
    *v = ManifoldVertex::from_interaction(si, si.bsdf()->eta(lambda));
    v->reflect = true;
    return true;
}

ReflectedConnection ExteriorReflection::connect(const ManifoldQuery& q, Sampler& sampler) const {
    ReflectedConnection out;
    const Scene& scene = *m_scene;
    const SurfaceInteraction& xb = *q.xb;
    // The connection is made with probability rho: the coin comes first, so that the others
    // cost nothing. Its uniform, stretched, seeds the generator that picks the caster and draws
    // y's half vector at rough glass. Without the connection the light sample's dimensions are
    // drawn all the same, so that every technique after it reads the same sampler dimensions in
    // every sample of a pixel (their stratification): the walk's draws, which happen only where
    // the connection gets that far, come from the generator instead.
    const double rho = m_settings->exterior_reflections, u = sampler.next_1d();
    if (!(u < rho)) {
        sampler.next_1d();  // as sample_light draws
        sampler.next_2d();
        return out;
    }
    const double u_caster = std::min(u / rho, 1.0 - 0x1p-53);
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, xb, q.ctx.wl, sampler, &light, &pmf, /*keep_dark=*/true);
    // Inside glass (an object in a glass ball) every path to a light leaves through an interface.
    if (!ls || (q.max_k >= 0 && q.max_k < 1) || q.media.inside()) return out;
    const CasterChoice casters(scene, xb.p, q.ctx.hero());
    if (casters.empty()) return out;
    PCG32 rng(uint64_t(u_caster * 0x1p53), 0x5eed);
    const Shape& caster = casters.pick(rng);
    const double p_caster = casters.probability_of(caster);
    HalfVectorDraws draws = HalfVectorDraws::of_pairs({Vec2(rng.next_double(), rng.next_double())});
    const LightPoint lp = light_point(scene, *light, *ls, xb.p);
    std::vector<ManifoldVertex> chain(1);
    if (!seed(caster, xb, *q.bsdf_b, lp.p, q.ctx.hero(), &chain[0])) return out;
    const MneeConnection c =
        mnee_connect(scene, *m_settings, xb, *q.bsdf_b, q.ctx, q.media, *light, pmf, lp, chain, draws);
    if (c.outcome != MneeOutcome::Success || !in_class(xb.p, chain[0].si, lp.p, q.ctx.hero()) || !(p_caster > 0))
        return out;
    out.density = rho * p_caster * c.pdf_mnee;
    out.pdf_bsdf = c.pdf_bsdf;
    out.pdf_nee = c.pdf_nee_last;
    // The path samples x_b's direction with its own density (caster sampling): it replaces
    // BSDF sampling's, the first factor of both other techniques' densities.
    if (q.directions && c.pdf_xb_direction > 0) {
        const Vec3 o_b = normalize(chain[0].p - xb.p);
        const double r =
            q.directions->pdf(xb, *q.bsdf_b, q.ctx.at(xb), xb.to_local(xb.wo), xb.to_local(o_b)) / c.pdf_xb_direction;
        out.pdf_bsdf *= r;
        out.pdf_nee *= r;
    }
    // mis_cutoff: where the other techniques' density dwarfs the connection's, the connection
    // keeps no weight, as density() answers for their copies of the path, without its walk (the
    // found path's density is its bound there).
    if (mis_cut_off(out.pdf_bsdf + out.pdf_nee, out.density, m_settings->mis_cutoff)) return out;
    out.found = true;
    out.y = chain[0].si;
    out.lp = lp;
    out.light = light;
    out.pmf = pmf;
    out.value = c.value / (rho * p_caster);
    return out;
}

double ExteriorReflection::density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const MediumStack& media_b,
                                   const SurfaceInteraction& y, const Light& light, double pmf, const Vec3& xc,
                                   const Vec3& nc, double lambda, double p_others) const {
    if (media_b.inside() || !in_class(xb.p, y, xc, lambda)) return 0;
    // Alg. 2 lines 1, 3 and 8 for the path as it is (at a rough y, with its own half vector).
    const double p = solution_density_bound(*m_scene, *m_settings, xb, bsdf_b, &y, 1, light, pmf, xc, nc, lambda);
    if (!(p > 0)) return 0;
    // The cutoff (as connect() cuts) first with the caster's probability at its largest, 1: NEE
    // from every rough y asks, and most of its paths are far from the mirror direction.
    const double rho = m_settings->exterior_reflections;
    if (mis_cut_off(p_others, rho * p, m_settings->mis_cutoff)) return 0;
    const double p_caster = CasterChoice(*m_scene, xb.p, lambda).probability_of(*y.shape);
    if (!(p_caster > 0)) return 0;
    const double bound = rho * p_caster * p;
    if (mis_cut_off(p_others, bound, m_settings->mis_cutoff)) return 0;
    // Lines 2 and 4-7: the seed connect() builds, walked; the path is the technique's only where
    // the walk reaches it. At a rough y the walk aims at the path's own half vector, read as the
    // unit slope the connection would have drawn for it (as mnee_pdf aims).
    std::vector<ManifoldVertex> target, seed_chain(1);
    std::vector<Vec2> slopes;
    if (!chain_of_path(xb, &y, 1, xc, lambda, &target, &slopes) || !target[0].reflect) return 0;
    if (!seed(*y.shape, xb, bsdf_b, xc, lambda, &seed_chain[0])) return 0;
    if (y.bsdf()->has_microfacet()) {
        seed_chain[0].has_unit_slope = true;
        seed_chain[0].unit_slope = slopes[0];
        seed_chain[0].h_target = target_from_unit_slope(seed_chain[0], slopes[0]);
    }
    const TangentBasis basis = light_point_basis(xc, nc, normalize(xc - xb.p));
    if (manifold_walk(m_scene, xb.p, seed_chain, basis, m_settings->walk).outcome != WalkOutcome::Converged) return 0;
    polish_solution(m_scene, xb.p, seed_chain, basis, m_settings->walk);
    polish_solution(m_scene, xb.p, target, basis, m_settings->walk);
    return same_solution(xb.p, seed_chain, target, xc) ? bound : 0.0;
}

}  // namespace snell
