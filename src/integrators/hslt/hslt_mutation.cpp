#include "integrators/hslt/hslt_mutation.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "camera/camera.h"
#include "core/stats.h"
#include "geometry/sphere.h"
#include "light/light.h"
#include "manifold/block_tridiagonal.h"
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

std::vector<double> half_vector_widths(const HsltContext& ctx, const HsltPath& path, const HsltMutationSettings& st) {
    const size_t n = path.chain.size();
    std::vector<double> sigma(n, 0.0);
    size_t perturbed = 0;
    for (size_t i = 0; i < n; ++i)
        if (!path.specular[i]) {
            sigma[i] = half_vector_width(path.chain[i], path.wl, st);
            ++perturbed;
        }
    if (!(st.footprint > 0) || perturbed == 0) return sigma;
    // d(film)/du_1: the pinhole's projection of x_1 moved along its tangent basis (central
    // differences; the projection is smooth and its scale is the distance to the pinhole).
    const ManifoldVertex& v1 = path.chain[0];
    const double e = 1e-6 * length(v1.p - path.x0);
    const Vec2 no_margin(1e30, 1e30);
    Vec2 r[4];
    double cos_theta;
    const Vec3 dirs[4] = {v1.dp_ds * e, v1.dp_ds * -e, v1.dp_dt * e, v1.dp_dt * -e};
    for (int k = 0; k < 4; ++k)
        if (!ctx.camera->raster_of(v1.p + dirs[k], &r[k], &cos_theta, no_margin)) return sigma;
    const Mat2 film_du = Mat2::from_columns((r[0] - r[1]) / (2 * e), (r[2] - r[3]) / (2 * e));
    // du_1/dh_j: block (1, j) of (dH/dX)^-1, the columns of M X = E_j.
    BlockTridiagonal m;
    std::vector<Vec2> c;
    if (!build_constraints(path.x0, path.chain, path.light_basis(), &m, &c)) return sigma;
    BlockLU lu;
    if (!lu.factor(m)) return sigma;
    const double per_vertex = st.footprint / std::sqrt(double(perturbed));
    for (size_t j = 0; j < n; ++j) {
        if (path.specular[j]) continue;
        std::vector<Mat2> unit(n, Mat2());
        unit[j] = Mat2::identity();
        const Mat2 g = film_du * lu.solve(unit)[0];
        // Root mean square of its singular values: pixels per unit of h_j, over directions.
        const double gain = std::sqrt(0.5 * (g.a * g.a + g.b * g.b + g.c * g.c + g.d * g.d));
        if (gain > 0 && std::isfinite(gain)) sigma[j] = std::min(sigma[j], per_vertex / gain);
    }
    return sigma;
}

HsltProposal perturb_half_vectors(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                                  HsltPath* y) {
    HsltProposal out;
    if (!(x.F > 0)) return out;
    *y = x;
    const std::vector<double> sigma_x = half_vector_widths(ctx, x, st);
    for (size_t i = 0; i < x.chain.size(); ++i) {
        if (x.specular[i]) continue;
        const Vec2 h = x.chain[i].h_target + gaussian2(rng) * sigma_x[i];
        if (!(h.x * h.x + h.y * h.y < 1)) return out;
        y->chain[i].h_target = h;
    }
    if (!walk(ctx, x.x0, y->chain, x.light_basis(), st) || !finish_proposal(ctx, x, 0, x.x0, st, y)) return out;
    // The widths depend on the path (its footprint, the roughness where each vertex lies):
    // T(y -> x) / T(x -> y).
    const std::vector<double> sigma_y = half_vector_widths(ctx, *y, st);
    double q = 1;
    for (size_t i = 0; i < x.chain.size(); ++i) {
        if (x.specular[i]) continue;
        const Vec2 d = y->chain[i].h_target - x.chain[i].h_target;
        q *= gaussian_density(d, sigma_y[i]) / gaussian_density(d, sigma_x[i]);
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

namespace {

// x_k moved on a spherical light: a Gaussian step in the tangent plane at x_k, projected
// radially onto the sphere. The new point's density depends on the angle between the two
// points alone, so the proposal is symmetric.
bool move_on_sphere(const Sphere& sphere, const SurfaceInteraction& xk, double width, PCG32& rng,
                    SurfaceInteraction* out) {
    const Vec3 c = sphere.center();
    const double r = sphere.radius();
    const Frame f = Frame::from_normal(normalize(xk.p - c));
    const Vec2 g = gaussian2(rng) * (width * r);
    const Vec3 p = c + normalize(xk.p + f.s * g.x + f.t * g.y - c) * r;
    return sphere.closest_point(p, 1e-6 * r + 1e-9 * length(p), out);
}

// x_k moved on any other emitting shape by a Gaussian step in its plane, of `width` times the
// radius of a disc of the shape's area. Kept only where the new point lies on the shape in the
// same plane (a rectangle, a disc, the flat part of a mesh): there the step is a translation
// within one plane, the same from either end, so the proposal is symmetric in area measure. A
// step off the shape, or onto a facet of another plane, is no proposal (curved meshes move
// within their flat facets only).
bool move_in_plane(const Shape& shape, const SurfaceInteraction& xk, double width, PCG32& rng,
                   SurfaceInteraction* out) {
    const double r = std::sqrt(shape.area() / kPi);
    const Frame f = Frame::from_normal(xk.ng);
    const Vec2 g = gaussian2(rng) * (width * r);
    const Vec3 p = xk.p + f.s * g.x + f.t * g.y;
    const double tol = 1e-6 * r + 1e-9 * length(p);
    if (!shape.closest_point(p, tol, out) || !(length(out->p - p) <= tol)) return false;
    return dot(out->ng, xk.ng) >= 1 - 1e-9;
}

}  // namespace

HsltProposal perturb_light(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                           HsltPath* y) {
    HsltProposal out;
    if (!(x.F > 0) || !x.light || !x.light->shape()) return out;
    const Shape& shape = *x.light->shape();
    SurfaceInteraction si;
    const auto* sphere = dynamic_cast<const Sphere*>(&shape);
    if (!(sphere ? move_on_sphere(*sphere, x.xk, st.light_width, rng, &si)
                 : move_in_plane(shape, x.xk, st.light_width, rng, &si)))
        return out;
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
