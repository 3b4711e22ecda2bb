#include "integrators/hslt/hslt_mutation.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "camera/camera.h"
#include "core/stats.h"
#include "geometry/sphere.h"
#include "light/light.h"
#include "manifold/mnee.h"
#include "scene/scene.h"

namespace snell {

namespace {

StatCounter hslt_walks{"hslt.walks", "manifold walks of the perturbations (forward and reverse)"};
StatCounter hslt_walks_converged{"hslt.walks_converged", "walks that converged"};
StatCounter hslt_walk_iterations{"hslt.walk_iterations", "iterations summed over converged walks"};
StatCounter hslt_not_admissible{"hslt.not_admissible", "converged proposals that scatter otherwise or are blocked"};
StatCounter hslt_not_reversible{"hslt.not_reversible", "proposals whose reverse walk missed the current path"};

Vec2 gaussian2(PCG32& rng) {
    // Box-Muller.
    const double u1 = 1.0 - rng.next_double(), u2 = rng.next_double();
    const double r = std::sqrt(-2.0 * std::log(u1));
    return {r * std::cos(2 * kPi * u2), r * std::sin(2 * kPi * u2)};
}

bool walk(const HsltContext& ctx, const Vec3& xb, std::vector<ManifoldVertex>& chain, const TangentBasis& xc,
          const HsltMutationSettings& st) {
    ++hslt_walks;
    const WalkResult r = manifold_walk(ctx.scene, xb, chain, xc, st.walk);
    if (r.outcome != WalkOutcome::Converged) return false;
    ++hslt_walks_converged;
    hslt_walk_iterations += uint64_t(r.iterations);
    return true;
}

// A walked path scatters as it says and every segment is clear.
bool admissible_and_visible(const HsltContext& ctx, const HsltPath& y) {
    const Scene& scene = *ctx.scene;
    if (!chain_admissible(y.x0, y.chain, y.xk.p)) return false;
    // x_1 -> x_0 (towards the pinhole: nothing lies at it), then the chain, then x_k.
    if (scene.occluded(scene.spawn_ray_to(y.chain[0].si, y.x0))) return false;
    for (size_t i = 0; i + 1 < y.chain.size(); ++i)
        if (scene.occluded(scene.spawn_ray_to(y.chain[i].si, y.chain[i + 1].si))) return false;
    return !scene.occluded(scene.spawn_ray_to(y.chain.back().si, y.xk));
}

bool same_vertices(const std::vector<ManifoldVertex>& a, const std::vector<ManifoldVertex>& b, double tol) {
    for (size_t i = 0; i < a.size(); ++i)
        if (!(length(a[i].p - b[i].p) <= tol)) return false;
    return true;
}

// The proposal's own half vectors as its targets (the walk converged to within its threshold).
void settle_targets(HsltPath* y) {
    for (size_t i = 0; i < y->chain.size(); ++i)
        y->chain[i].h_target = y->specular[i] ? Vec2(0, 0) : hslt_half_vector(*y, i);
}

// Admissible, visible, carrying light, perturbable; then the reverse walk (from y's vertices
// with x's targets, between `xb` and x's light point) must come back to x's chain from `first`.
bool finish_proposal(const HsltContext& ctx, const HsltPath& x, size_t first, const Vec3& xb,
                     const HsltMutationSettings& st, HsltPath* y) {
    if (!admissible_and_visible(ctx, *y) || !evaluate_hslt_path(*ctx.scene, *ctx.camera, *ctx.film, y) || !(y->F > 0)) {
        ++hslt_not_admissible;
        return false;
    }
    settle_targets(y);
    std::vector<ManifoldVertex> back(y->chain.begin() + std::ptrdiff_t(first), y->chain.end());
    for (size_t i = 0; i < back.size(); ++i) back[i].h_target = x.chain[first + i].h_target;
    const std::vector<ManifoldVertex> want(x.chain.begin() + std::ptrdiff_t(first), x.chain.end());
    if (!walk(ctx, xb, back, x.light_basis(), st) || !same_vertices(back, want, st.tolerance * ctx.scene_extent)) {
        ++hslt_not_reversible;
        return false;
    }
    return true;
}

double gaussian_density(const Vec2& d, double sigma) {
    return std::exp(-(d.x * d.x + d.y * d.y) / (2 * sigma * sigma)) / (2 * kPi * sigma * sigma);
}

}  // namespace

double half_vector_width(const ManifoldVertex& v, const SampledWavelengths& wl, const HsltMutationSettings& st) {
    if (v.bsdf && v.bsdf->has_microfacet()) {
        const BSDFContext ctx{wl, TransportMode::Radiance};
        if (const auto d = v.bsdf->microfacet(ctx.at(v.si)))
            return std::min(st.width, st.rough_width * std::max(d->alpha_u(), d->alpha_v()));
    }
    return st.width;
}

HsltProposal perturb_half_vectors(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                                  HsltPath* y) {
    HsltProposal out;
    if (!(x.F > 0)) return out;
    *y = x;
    std::vector<double> sigma_x(x.chain.size(), 0);
    for (size_t i = 0; i < x.chain.size(); ++i) {
        if (x.specular[i]) continue;
        sigma_x[i] = half_vector_width(x.chain[i], x.wl, st);
        const Vec2 h = x.chain[i].h_target + gaussian2(rng) * sigma_x[i];
        if (!(h.x * h.x + h.y * h.y < 1)) return out;
        y->chain[i].h_target = h;
    }
    if (!walk(ctx, x.x0, y->chain, x.light_basis(), st) || !finish_proposal(ctx, x, 0, x.x0, st, y)) return out;
    // The Gaussians' widths follow the roughness where each vertex lies: T(y -> x) / T(x -> y).
    double q = 1;
    for (size_t i = 0; i < x.chain.size(); ++i) {
        if (x.specular[i]) continue;
        const Vec2 d = y->chain[i].h_target - x.chain[i].h_target;
        q *= gaussian_density(d, half_vector_width(y->chain[i], y->wl, st)) / gaussian_density(d, sigma_x[i]);
    }
    out.valid = true;
    out.ratio = y->F / x.F * q;
    return out;
}

HsltProposal perturb_lens(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                          HsltPath* y) {
    HsltProposal out;
    const double fx = hslt_lens_density(x);
    if (!(fx > 0)) return out;
    const Scene& scene = *ctx.scene;
    *y = x;
    const Vec2 raster = x.raster + gaussian2(rng) * st.lens_width;
    const Ray ray = ctx.camera->generate_ray(raster);
    SurfaceInteraction si;
    if (!scene.intersect(ray, &si) || si.shape != x.chain[0].shape) return out;
    ManifoldVertex v1 = ManifoldVertex::from_interaction(si, x.chain[0].eta);
    v1.reflect = x.chain[0].reflect;
    y->chain[0] = v1;
    // x_2 .. x_{k-1} keep their half vectors (their targets are x's own).
    if (x.chain.size() > 1) {
        std::vector<ManifoldVertex> sub(y->chain.begin() + 1, y->chain.end());
        if (!walk(ctx, v1.p, sub, x.light_basis(), st)) return out;
        std::copy(sub.begin(), sub.end(), y->chain.begin() + 1);
    }
    if (!admissible_and_visible(ctx, *y) || !evaluate_hslt_path(scene, *ctx.camera, *ctx.film, y) || !(y->F > 0)) {
        ++hslt_not_admissible;
        return out;
    }
    settle_targets(y);
    // Reverse: x's film position gives x's x_1 again (the same ray); the walk from y's vertices
    // must return to x's.
    const Ray back_ray = ctx.camera->generate_ray(x.raster);
    SurfaceInteraction back_si;
    const double tol = st.tolerance * ctx.scene_extent;
    if (!scene.intersect(back_ray, &back_si) || back_si.shape != x.chain[0].shape ||
        !(length(back_si.p - x.chain[0].p) <= tol)) {
        ++hslt_not_reversible;
        return out;
    }
    if (x.chain.size() > 1) {
        std::vector<ManifoldVertex> back(y->chain.begin() + 1, y->chain.end());
        for (size_t i = 0; i < back.size(); ++i) back[i].h_target = x.chain[i + 1].h_target;
        const std::vector<ManifoldVertex> want(x.chain.begin() + 1, x.chain.end());
        if (!walk(ctx, back_si.p, back, x.light_basis(), st) || !same_vertices(back, want, tol)) {
            ++hslt_not_reversible;
            return out;
        }
    }
    const double fy = hslt_lens_density(*y);
    if (!(fy > 0)) return out;
    out.valid = true;
    out.ratio = fy / fx;
    return out;
}

HsltProposal perturb_light(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                           HsltPath* y) {
    HsltProposal out;
    if (!(x.F > 0) || !x.light || !x.light->shape()) return out;
    const auto* sphere = dynamic_cast<const Sphere*>(x.light->shape());
    if (!sphere) return out;
    // A Gaussian step in the tangent plane at x_k, projected radially onto the sphere: the
    // density of the new point depends on the angle between the two alone (symmetric).
    const Vec3 c = sphere->center();
    const double r = sphere->radius();
    const Frame f = Frame::from_normal(normalize(x.xk.p - c));
    const Vec2 g = gaussian2(rng) * (st.light_width * r);
    const Vec3 p = c + normalize(x.xk.p + f.s * g.x + f.t * g.y - c) * r;
    SurfaceInteraction si;
    if (!sphere->closest_point(p, 1e-6 * r + 1e-9 * length(p), &si)) return out;
    *y = x;
    y->xk = si;
    y->xk.wo = Vec3();
    if (!walk(ctx, x.x0, y->chain, y->light_basis(), st)) return out;
    if (!finish_proposal(ctx, x, 0, x.x0, st, y)) return out;
    out.valid = true;
    out.ratio = y->F / x.F;
    return out;
}

}  // namespace snell
