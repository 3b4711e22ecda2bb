#include "manifold/surface_seed.h"

#include <algorithm>
#include <cmath>

#include "bsdf/bsdf.h"
#include "bsdf/fresnel.h"
#include "geometry/shape.h"
#include "manifold/seed_path.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

namespace {

// Refraction of the travel direction d about the unit normal m (either orientation) from IOR n1
// into n2; false for total internal reflection.
bool refract_about(const Vec3& d, Vec3 m, double n1, double n2, Vec3* out) {
    double cos_i = -dot(d, m);
    if (cos_i < 0) {
        m = -m;
        cos_i = -cos_i;
    }
    const double e = n1 / n2, sin2_t = e * e * std::max(0.0, 1 - cos_i * cos_i);
    if (sin2_t >= 1) return false;
    *out = normalize(d * e + m * (e * cos_i - std::sqrt(1 - sin2_t)));
    return true;
}

// Follows `ray` (aimed at a point of `caster`) through every refractive interface it meets,
// refracting about each vertex's target half vector (`draws` slot i, in hit order) or, without
// `draws`, about the shading normal, until it meets anything else or leaves the scene.
SurfaceSeedEnd trace_through(const Scene& scene, Ray ray, const Shape& caster, double lambda,
                             const MneeSettings& settings, HalfVectorDraws* draws, PCG32* scatter,
                             std::vector<ManifoldVertex>* chain, Vec3* exit_dir) {
    chain->clear();
    ray.tmax = kInfinity;  // beyond the drawn point too: the first hit must be the caster, wherever on it
    for (int i = 0;; ++i) {
        SurfaceInteraction si;
        if (!scene.intersect(ray, &si)) break;
        const BSDF* bsdf = si.bsdf();
        if (i == 0 && si.shape != &caster) return SurfaceSeedEnd::MissedCaster;
        if (si.emitter() || !is_manifold_interface(bsdf, lambda)) break;
        if (i >= settings.max_vertices) return SurfaceSeedEnd::TooMany;
        ManifoldVertex v = ManifoldVertex::from_interaction(si, bsdf->eta(lambda));
        // The vertex's target half vector (slot i, as set_half_vectors reads it), in world space
        // on the side of n.
        const Vec2 h = draws ? target_half_vector(v, i, *draws) : Vec2(0, 0);
        v.h_target = h;
        const Vec3 m = v.s * h.x + v.t * h.y + v.n * std::sqrt(std::max(0.0, 1 - h.x * h.x - h.y * h.y));
        const bool entering = dot(ray.d, v.ng) < 0;
        Vec3 d;
        const bool refracts = refract_about(ray.d, m, entering ? 1.0 : v.eta, entering ? v.eta : 1.0, &d);
        if (settings.reflections && scatter) {
            // Reflect with Fresnel's probability (always under total internal reflection).
            const double r = fresnel_dielectric(std::abs(dot(ray.d, m)), entering ? v.eta : 1.0 / v.eta).R;
            v.reflect = !refracts || scatter->next_double() < r;
            if (v.reflect) d = ray.d - m * (2 * dot(ray.d, m));
        } else if (!refracts) {
            return SurfaceSeedEnd::TotalInternalReflection;
        }
        chain->push_back(v);
        ray = scene.spawn_ray(si, d);
    }
    if (exit_dir) *exit_dir = ray.d;
    return chain->empty() ? SurfaceSeedEnd::MissedCaster : SurfaceSeedEnd::Ok;
}

}  // namespace

SurfaceSeedEnd trace_surface_seed(const Scene& scene, const SurfaceInteraction& xb, const Shape& caster, const Vec2& u,
                                  double lambda, const MneeSettings& settings, HalfVectorDraws* draws,
                                  std::vector<ManifoldVertex>* chain, PCG32* scatter, Vec3* exit_dir) {
    const auto y = caster.sample_from(xb.p, u);
    const SurfaceSeedEnd end = y ? trace_through(scene, scene.spawn_ray_to(xb, y->p, std::max(0.0, y->p_error)), caster,
                                                 lambda, settings, draws, scatter, chain, exit_dir)
                                 : SurfaceSeedEnd::MissedCaster;
    walk_counters::surface_seed_end.add(uint32_t(end));
    return end;
}

SurfaceSeedEnd trace_light_seed(const Scene& scene, const Vec3& xc, const Shape& caster, const Vec2& u, double lambda,
                                const MneeSettings& settings, HalfVectorDraws& draws,
                                std::vector<ManifoldVertex>* chain, PCG32* scatter) {
    SurfaceSeedEnd end = SurfaceSeedEnd::MissedCaster;
    if (const auto y = caster.sample_from(xc, u)) {
        Ray ray{xc, normalize(y->p - xc), 0.0, kInfinity};
        ray.tmin = Scene::ray_tmin(xc, length(y->p - xc));
        end = trace_through(scene, ray, caster, lambda, settings, nullptr, scatter, chain, nullptr);
    }
    if (end == SurfaceSeedEnd::Ok) {
        // Traced from the light: the chain runs x_c -> x_b. Reverse it and give each vertex the
        // target of its slot counted from x_b.
        std::reverse(chain->begin(), chain->end());
        for (size_t i = 0; i < chain->size(); ++i)
            (*chain)[i].h_target = target_half_vector((*chain)[i], int(i), draws);
    }
    walk_counters::surface_seed_end.add(uint32_t(end));
    return end;
}

double seed_miss(const std::vector<ManifoldVertex>& chain, const Vec3& exit_dir, const Vec3& xc) {
    const ManifoldVertex& last = chain.back();
    const Vec3 to_light = normalize(xc - last.p);
    const double miss = 1 - dot(exit_dir, to_light);
    // Still inside the glass (the light lies across the last interface from the ray): the chain
    // is one interface short of any path to the light.
    return dot(exit_dir, last.ng) * dot(to_light, last.ng) < 0 ? 2 + miss : miss;
}

}  // namespace snell
