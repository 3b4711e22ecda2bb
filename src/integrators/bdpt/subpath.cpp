#include "integrators/bdpt/subpath.h"

#include <algorithm>
#include <cmath>

#include "core/warp.h"
#include "geometry/shape.h"
#include "integrators/scatter.h"
#include "light/light_sampler.h"
#include "light/point.h"
#include "light/spot.h"
#include "scene/scene.h"

namespace snell::bdpt {

void random_walk(const Scene& scene, Ray ray, Sampler& sampler, const SampledWavelengths& wl, SampledSpectrum beta,
                 double pdf_dir, size_t max_vertices, int rr_depth, TransportMode mode, std::vector<Vertex>& path,
                 Escape* escape) {
    const BSDFContext ctx{wl, mode};
    const BSDFContext ctx_rev{wl,
                              mode == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance};
    MediumStack media;
    Throughput tp{beta, 1.0, !path.empty() && path.back().hero_only};
    while (path.size() < max_vertices) {
        SurfaceInteraction si;
        if (!scene.intersect(ray, &si)) {
            if (escape) *escape = {true, ray.d, tp.beta, pdf_dir};
            break;
        }
        // A light subpath may start inside a dielectric (a light in coloured glass): it finds
        // out when it leaves an interface from the inside with nothing on its stack, and the
        // segment it just travelled lay in that interior. (Camera subpaths start outside.)
        if (mode == TransportMode::Importance && !media.inside() && dot(ray.d, si.ng) > 0) {
            const BSDF* b = si.bsdf();
            if (b && (b->eta(wl.hero()) != 1.0 || b->interior_absorption()))
                media.cross(b->interior_absorption(), true);
        }
        if (media.inside()) tp.beta *= media.transmittance(si.t, wl);
        Vertex v;
        v.si = si;
        v.bsdf = si.bsdf();
        v.light = si.emitter();
        v.beta = tp.beta;
        v.media = media;
        v.hero_only = tp.hero_only;
        v.pdf_fwd = to_area(pdf_dir, path.back(), v);
        path.push_back(v);
        if (path.size() >= max_vertices || !v.bsdf) break;

        Vertex& cur = path.back();
        const Vec3 wo = si.to_local(si.wo);
        const auto bs = cur.bsdf->sample(ctx.at(cur.si), wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || bs->weight.is_zero()) break;
        const Vec3 wi = si.to_world(bs->wi);
        double pdf_rev_dir = 0;
        if (bs->is_delta()) {
            cur.delta = true;
            pdf_dir = 0;
        } else {
            pdf_dir = bs->pdf;
            pdf_rev_dir = cur.bsdf->pdf(ctx_rev.at(cur.si), bs->wi, wo);
        }
        tp.scatter(*bs, wl, mode);
        if (mode == TransportMode::Importance) tp.beta *= shading_correction(si, si.wo, wi);
        path[path.size() - 2].pdf_rev = to_area(pdf_rev_dir, cur, path[path.size() - 2]);
        if (crosses_interior(*cur.bsdf, *bs)) cross_interface(media, si, *cur.bsdf);
        ray = scene.spawn_ray(si, wi);
        // Roulette after the same number of surface vertices as the path tracer.
        if (int(path.size()) - 1 >= rr_depth && !tp.survives_roulette(sampler.next_1d())) break;
    }
}

void light_subpath(const Scene& scene, const SceneDisk& disk, Sampler& sampler, const SampledWavelengths& wl,
                   size_t max_vertices, int rr_depth, std::vector<Vertex>& path) {
    path.clear();
    double pmf = 0;
    const Light* light = scene.light_sampler().sample(sampler.next_1d(), &pmf);
    const Vec2 u_pos = sampler.next_2d(), u_dir = sampler.next_2d();
    if (!light || !(pmf > 0) || max_vertices == 0) return;
    Vertex y0;
    y0.type = VertexType::Light;
    y0.light = light;
    if (light->is_infinite()) {
        const auto ls = light->sample_li({disk.center, Vec3()}, u_dir, wl);
        if (!ls || !(ls->pdf > 0) || ls->Le.is_zero()) return;
        y0.infinite = true;
        y0.dir = ls->wi;
        y0.pdf_fwd = pmf * ls->pdf;
        y0.beta = SampledSpectrum(1.0 / (pmf * ls->pdf));  // radiance (irradiance) is evaluated per connection
        const Frame f = Frame::from_normal(ls->wi);
        const Vec2 q = warp::square_to_uniform_disk_concentric(u_pos) * disk.radius;
        y0.si.p = disk.center + ls->wi * disk.radius + f.s * q.x + f.t * q.y;
        path.push_back(y0);
        random_walk(scene, Ray{y0.si.p, -ls->wi}, sampler, wl, ls->Le / (pmf * ls->pdf * disk.pdf()), disk.pdf(),
                    max_vertices, rr_depth, TransportMode::Importance, path, nullptr);
        return;
    }
    double pdf_pos = 1, pdf_dir = 0;
    SampledSpectrum le;
    Vec3 w;
    if (delta_position(*light)) {
        y0.si.p = light->position();
        w = warp::square_to_uniform_sphere(u_dir);
        pdf_dir = kInv4Pi;
        le = light->emitted(y0.si.p, Vec3(), Vec2(), w, wl);
    } else {
        const Shape* shape = light->shape();
        if (!shape) return;
        const ShapeSample ss = shape->sample_area(u_pos);
        pdf_pos = ss.pdf;
        y0.si.p = ss.p;
        y0.si.n = y0.si.ng = ss.n;
        y0.si.shading = Frame::from_normal(ss.n);
        // The shape (and no triangle) for the ray offsets: its rounding bound keeps rays
        // leaving the light, and shadow rays reaching it, clear of its own surface.
        y0.si.shape = shape;
        y0.si.prim = ~0u;
        const Vec3 w_local = warp::square_to_cosine_hemisphere(u_dir);
        w = y0.si.to_world(w_local);
        pdf_dir = warp::square_to_cosine_hemisphere_pdf(w_local);
        y0.si.uv = ss.uv;
        le = light->le(ss.p, ss.n, ss.uv, w, wl) * w_local.z;
    }
    if (!(pdf_pos > 0)) return;
    y0.pdf_fwd = pmf * pdf_pos;
    y0.beta = SampledSpectrum(1.0 / (pmf * pdf_pos));  // emission is evaluated per connection (s = 1)
    path.push_back(y0);
    if (le.is_zero() || !(pdf_dir > 0)) return;
    const Ray ray = y0.has_normal() ? scene.spawn_ray(y0.si, w) : Ray{y0.si.p, w};
    random_walk(scene, ray, sampler, wl, le / (pmf * pdf_pos * pdf_dir), pdf_dir, max_vertices, rr_depth,
                TransportMode::Importance, path, nullptr);
}

}  // namespace snell::bdpt
