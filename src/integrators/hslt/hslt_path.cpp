#include "integrators/hslt/hslt_path.h"

#include <algorithm>
#include <cmath>

#include "bsdf/bsdf.h"
#include "camera/camera.h"
#include "core/medium_stack.h"
#include "light/light.h"
#include "manifold/block_tridiagonal.h"
#include "manifold/manifold_walk.h"
#include "manifold/mnee.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

namespace snell {

TangentBasis HsltPath::light_basis() const {
    const Vec3 arrival = normalize(xk.p - (chain.empty() ? x0 : chain.back().p));
    return light_point_basis(xk.p, xk.ng, arrival);
}

namespace {

// Directions at chain vertex i: towards the camera side (wi) and towards the light side (wo).
void directions(const HsltPath& path, size_t i, Vec3* wi, Vec3* wo) {
    const Vec3& p = path.chain[i].p;
    *wi = normalize((i == 0 ? path.x0 : path.chain[i - 1].p) - p);
    if (i + 1 < path.chain.size())
        *wo = normalize(path.chain[i + 1].p - p);
    else
        *wo = path.infinite ? path.escape_dir : normalize(path.xk.p - p);
}

// |det| of the constraint blocks of x_first .. x_{k-1} between x_b (the vertex before x_first)
// and x_k: the pivots' product, and the product of the blocks C_i = dh_i/dx_{i+1}.
bool constraint_dets(const HsltPath& path, size_t first, double* det_m, double* det_c) {
    const std::vector<ManifoldVertex> sub(path.chain.begin() + std::ptrdiff_t(first), path.chain.end());
    const Vec3 xb = first == 0 ? path.x0 : path.chain[first - 1].p;
    BlockTridiagonal m;
    std::vector<Vec2> c;
    if (!build_constraints(xb, sub, path.light_basis(), &m, &c)) return false;
    BlockLU lu;
    if (!lu.factor(m)) return false;
    *det_m = lu.abs_det();
    *det_c = 1;
    for (const Mat2& ci : m.C) *det_c *= std::abs(ci.det());
    return *det_m > 0 && std::isfinite(*det_m) && std::isfinite(*det_c);
}

}  // namespace

Vec2 hslt_half_vector(const HsltPath& path, size_t i) {
    Vec3 wi, wo;
    directions(path, i, &wi, &wo);
    const ManifoldVertex& v = path.chain[i];
    return tangential(v, generalized_half_vector(v, wi, wo));
}

bool sample_hslt_path(const Scene& scene, const PerspectiveCamera& camera, const FilmSpec& film,
                      const std::vector<double>& depth_pmf, int spectral_samples, bool hide_emitters, PCG32& rng,
                      HsltPath* path) {
    *path = HsltPath{};
    ++render_stats::paths;
    // The length first (a chain visits one length at a time), then the film position and the
    // wavelengths, then one BSDF sample per vertex.
    double u = rng.next_double(), acc = 0;
    size_t k = depth_pmf.size();
    for (size_t j = 0; j < depth_pmf.size(); ++j) {
        acc += depth_pmf[j];
        if (u < acc) {
            k = j + 1;
            break;
        }
    }
    while (k > 0 && !(depth_pmf[k - 1] > 0)) --k;  // rounding past the last nonzero entry
    if (k == 0) return false;
    path->depth_pmf = depth_pmf[k - 1];
    if (k == 1 && hide_emitters) return false;
    const Vec2 o = film.sample_origin(), e = film.sample_extent();
    path->raster = Vec2(o.x + rng.next_double() * e.x, o.y + rng.next_double() * e.y);
    const double u0 = rng.next_double(), u1 = rng.next_double();
    path->wl = SampledWavelengths::sample_visible({u0, u1}, spectral_samples);
    const BSDFContext ctx{path->wl, TransportMode::Radiance};
    Ray ray = camera.generate_ray(path->raster);
    path->x0 = ray.o;
    for (size_t i = 0; i < k; ++i) {
        SurfaceInteraction si;
        if (!scene.intersect(ray, &si)) {
            if (i + 1 != k || scene.infinite_lights().empty()) return false;
            path->infinite = true;
            path->light = scene.infinite_lights().front();
            path->escape_dir = ray.d;
            break;
        }
        if (i + 1 == k) {
            if (!si.emitter()) return false;
            path->light = si.emitter();
            path->xk = si;
            break;
        }
        const BSDF* bsdf = si.bsdf();
        if (!bsdf) return false;
        const double uc = rng.next_double();
        const Vec2 ub(rng.next_double(), rng.next_double());
        const auto bs = bsdf->sample(ctx.at(si), si.to_local(si.wo), uc, ub);
        if (!bs || bs->weight.is_zero()) return false;
        const Vec3 wi = si.to_world(bs->wi);
        ManifoldVertex v = ManifoldVertex::from_interaction(si, bsdf->eta(path->wl.hero()));
        v.reflect = dot(si.wo, si.ng) * dot(wi, si.ng) > 0;
        path->chain.push_back(v);
        path->specular.push_back(bs->is_delta() ? 1 : 0);
        ray = scene.spawn_ray(si, wi);
    }
    for (size_t i = 0; i < path->chain.size(); ++i) path->chain[i].h_target = hslt_half_vector(*path, i);
    return evaluate_hslt_path(scene, camera, film, path);
}

bool evaluate_hslt_path(const Scene& scene, const PerspectiveCamera& camera, const FilmSpec& film, HsltPath* path) {
    path->C = SampledSpectrum();
    path->xyz = Vec3();
    path->F = 0;
    const BSDFContext ctx{path->wl, TransportMode::Radiance};
    // The camera: the film position of x_0 -> x_1 (the pinhole's importance, per unit area of
    // x_1, is 1 / cos^3 of the angle to the axis times G's cosine at x_1 over the distance
    // squared, up to a constant; path tracing's weight for it is 1).
    const Vec3 x1 =
        path->chain.empty() ? (path->infinite ? path->x0 + path->escape_dir : path->xk.p) : path->chain[0].p;
    double cos_cam = 0;
    Vec2 raster;
    if (!camera.raster_of(x1, &raster, &cos_cam, camera.film().filter_margin() + Vec2(1, 1))) return false;
    // Large steps place the film position uniformly over the window grown by the filter
    // margin: outside it the target is zero.
    const Vec2 o = film.sample_origin(), e = film.sample_extent();
    if (!(raster.x >= o.x && raster.x < o.x + e.x && raster.y >= o.y && raster.y < o.y + e.y)) return false;
    path->raster = raster;
    SampledSpectrum C(1.0 / path->depth_pmf), S(1.0);
    path->camera_factor = 1;
    if (!path->chain.empty() || !path->infinite) {
        const Vec3 d = x1 - path->x0;
        const Vec3 ng1 = path->chain.empty() ? path->xk.ng : path->chain[0].ng;
        path->camera_factor = std::abs(dot(ng1, normalize(d))) / (length_squared(d) * cos_cam * cos_cam * cos_cam);
        S *= path->camera_factor;
    }
    bool hero_only = false;
    // Beer-Lambert inside absorbing interiors, entered and left where the path refracts (as
    // the path tracer's media stack does; the camera lies outside every interior).
    MediumStack media;
    SampledSpectrum tr(1.0);
    for (size_t i = 0; i < path->chain.size(); ++i) {
        const ManifoldVertex& v = path->chain[i];
        Vec3 wi, wo;
        directions(*path, i, &wi, &wo);
        if (media.inside())
            tr *= media.transmittance(length(v.p - (i == 0 ? path->x0 : path->chain[i - 1].p)), path->wl);
        if (!v.reflect && (v.eta != 1.0 || v.bsdf->interior_absorption()))
            media.cross(v.bsdf->interior_absorption(), dot(wi, v.ng) > 0);
        if ((dot(wi, v.ng) * dot(wo, v.ng) > 0) != v.reflect) return false;
        // BSDF convention: its wo is the camera side (our wi).
        const Vec3 wi_l = v.si.to_local(wi), wo_l = v.si.to_local(wo);
        const BSDFContext vctx = ctx.at(v.si);
        if (path->specular[i]) {
            const SampledSpectrum kappa = v.bsdf->eval_delta(vctx, wi_l, wo_l);  // Eq. 9
            const double p = v.bsdf->pdf_delta(vctx, wi_l, wo_l);
            if (kappa.is_zero() || !(p > 0)) return false;
            C *= kappa / p;
            S *= kappa;
            hero_only = hero_only || (!v.reflect && v.bsdf->dispersive());
        } else {
            const SampledSpectrum f = v.bsdf->eval(vctx, wi_l, wo_l);
            const double p = v.bsdf->pdf(vctx, wi_l, wo_l);
            const Vec3 h = generalized_half_vector(v, wi, wo);
            const double cos_h = std::abs(dot(h, v.n));
            if (f.is_zero() || !(p > 0) || !(cos_h > 0)) return false;
            C *= f * (std::abs(wo_l.z) / p);
            // Per projected solid angle of h (Eq. 6's factor): f_r |cos o| |do/dh| / |cos h|.
            S *= f * (std::abs(wo_l.z) * half_vector_jacobian(v, wi, wo, h) / cos_h);
        }
    }
    SampledSpectrum le;
    if (path->infinite) {
        for (const Light* l : scene.infinite_lights()) le += l->le_escaped(path->escape_dir, path->wl);
    } else {
        const Vec3 prev = path->chain.empty() ? path->x0 : path->chain.back().p;
        le = path->light->le(path->xk.p, path->xk.n, path->xk.uv, normalize(prev - path->xk.p), path->wl);
    }
    if (media.inside()) {
        if (path->infinite) return false;  // escaping from inside an interior
        tr *=
            media.transmittance(length(path->xk.p - (path->chain.empty() ? path->x0 : path->chain.back().p)), path->wl);
    }
    if (le.is_zero() || tr.is_zero()) return false;
    C *= le * tr;
    S *= le * tr;
    if (hero_only) {
        C = path->wl.hero_only(C);
        S = path->wl.hero_only(S);
    }
    path->hero_only = hero_only;
    const Vec3 xyz = path->wl.to_xyz(C);
    if (!(hslt_importance(xyz) > 0) || !std::isfinite(xyz.x) || !std::isfinite(xyz.y) || !std::isfinite(xyz.z))
        return false;
    path->C = C;
    path->xyz = xyz;
    // Half-vector coordinates exist with a vertex between the fixed ends.
    double det_m = 0, det_c = 0;
    if (!path->infinite && !path->chain.empty() && constraint_dets(*path, 0, &det_m, &det_c)) {
        path->s_importance = hslt_importance(path->wl.to_xyz(S));
        path->det_c = det_c;
        const double F = path->s_importance * det_c / det_m;
        if (F > 0 && std::isfinite(F)) path->F = F;
    }
    return true;
}

double hslt_lens_density(const HsltPath& path) {
    // The lens perturbation's coordinates are the film position and the half vectors of
    // x_2 .. x_{k-1}: W G_0 |dx_1/d(film)| is constant for a pinhole, so the density is
    // T(S) / (W G_0) |det C| over the matrix of x_2 .. x_{k-1} between x_1 and x_k (x_1's block
    // C_1 stays: rho_1 |det C_1| is f_r |cos| G of x_1's segment).
    if (path.chain.empty() || path.infinite || path.specular[0] || !(path.F > 0)) return 0;
    double det_m1 = 1, det_c1 = 1;
    if (path.chain.size() > 1 && !constraint_dets(path, 1, &det_m1, &det_c1)) return 0;
    const double d = path.s_importance / path.camera_factor * path.det_c / det_m1;
    return d > 0 && std::isfinite(d) ? d : 0;
}

}  // namespace snell
