#include "integrators/bdpt/bdpt.h"

#include <cmath>
#include <vector>

#include "bsdf/bsdf.h"
#include "camera/camera.h"
#include "core/spectrum.h"
#include "core/medium_stack.h"
#include "core/stats.h"
#include "core/warp.h"
#include "geometry/scene.h"
#include "geometry/shape.h"
#include "integrators/mis.h"
#include "light/point.h"
#include "light/spot.h"
#include "render/renderer.h"

namespace snell {

namespace {

// With max_depth = -1 subpaths end by Russian roulette; this cap only bounds memory (a path
// of this many vertices has a vanishing probability under roulette).
constexpr int kUnboundedVertices = 128;

enum class VertexType { Camera, Light, Surface };

/// The pinhole z_0 as a vertex. Camera rays are spread uniformly over the output window of
/// the image plane (at unit distance, area A), so a ray at angle theta to the optical axis has
/// solid-angle density 1 / (A cos^3 theta); the importance of the window that makes light
/// tracing estimate the same pixel means is W_e = 1 / (A cos^4 theta) (Veach's thesis,
/// Sec. 10.3.4; pbrt-v3 Sec. 16.1 uses the whole film where we use the crop window).
struct Pinhole {
    const PerspectiveCamera* camera = nullptr;
    FilmSpec window;
    double area = 0;  // A

    Pinhole(const PerspectiveCamera& cam, const FilmSpec& spec)
        : camera(&cam), window(spec), area(cam.pixel_plane_area() * double(spec.out_width()) * double(spec.out_height())) {}
    /// Raster position (full film) at which p is seen, when inside the output window.
    bool raster(const Vec3& p, Vec2* r, double* cos_theta) const {
        if (!camera->raster_of(p, r, cos_theta)) return false;
        return r->x >= window.crop_x && r->x < window.crop_x + window.out_width() && r->y >= window.crop_y &&
               r->y < window.crop_y + window.out_height();
    }
    double pdf_dir(double cos_theta) const { return cos_theta > 0 ? 1.0 / (area * cos_theta * cos_theta * cos_theta) : 0.0; }
    double importance(double cos_theta) const { return cos_theta > 0 ? pdf_dir(cos_theta) / cos_theta : 0.0; }
};

/// One subpath vertex. Densities are in area measure at this vertex: pdf_fwd as its own
/// subpath sampled it, pdf_rev as the opposite subpath would (0 through delta lobes).
struct Vertex {
    VertexType type = VertexType::Surface;
    SurfaceInteraction si;      // camera: p only; light: p and n (zero for point and spot)
    const BSDF* bsdf = nullptr;
    const Light* light = nullptr;  // light vertex: its light; surface vertex: the shape's emitter
    double beta = 0;            // throughput of the subpath up to and including this vertex
    double pdf_fwd = 0, pdf_rev = 0;
    bool delta = false;         // scattered by a delta lobe on its own subpath
    MediumStack media;          // medium on the side the subpath arrived from
    const Pinhole* pinhole = nullptr;  // camera vertex only
    // A vertex at infinity (the start of a light subpath from an environment or directional
    // light, or where a camera subpath escapes): `dir` points from the scene towards it, and
    // its densities are solid-angle densities of that direction (Veach's thesis, Sec. 10.3.5).
    bool infinite = false;
    Vec3 dir;

    bool has_normal() const { return length_squared(si.ng) > 0; }
    bool connectible() const {
        return type != VertexType::Surface || (bsdf && bsdf->is_smooth_sampled());
    }
};

bool delta_position(const Light& l) { return l.kind() == LightKind::Point || l.kind() == LightKind::Spot; }
// Lights no camera subpath can hit: a delta position, or the directional light's delta direction.
bool delta_origin(const Light& l) { return delta_position(l) || l.kind() == LightKind::Directional; }

// Unit direction from vertex `from` towards vertex `to` (which may lie at infinity).
Vec3 direction(const Vertex& from, const Vertex& to) {
    if (to.infinite) return to.dir;
    if (from.infinite) return -from.dir;
    return normalize(to.si.p - from.si.p);
}

/// Light subpaths from lights at infinity start on a disk of the scene's bounding-sphere radius
/// R facing the sampled direction: area density 1 / (pi R^2) across the beam.
struct SceneDisk {
    Vec3 center;
    double radius = 1;
    explicit SceneDisk(const Bounds3& b) {
        if (b.valid()) {
            center = b.center();
            radius = 0.5 * length(b.extent());
        }
        if (!(radius > 0)) radius = 1;
    }
    double pdf() const { return 1.0 / (kPi * radius * radius); }
};

// Solid-angle density at `from` of the direction to `to`, converted to area measure at `to`
// (geometric normal: the area measure of the surface). Towards a vertex at infinity the
// density stays a solid-angle density; from one, `pdf_dir` is the planar density across the
// beam (SceneDisk), projected onto the surface at `to`.
double to_area(double pdf_dir, const Vertex& from, const Vertex& to) {
    if (to.infinite) return pdf_dir;
    if (from.infinite) return to.has_normal() ? pdf_dir * std::abs(dot(to.si.ng, from.dir)) : pdf_dir;
    const Vec3 d = to.si.p - from.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return 0;
    double pdf = pdf_dir / d2;
    if (to.has_normal()) pdf *= std::abs(dot(to.si.ng, d)) / std::sqrt(d2);
    return pdf;
}

// Area density at `next` with which a subpath continuing from `v` (reached from `prev`, which
// for a light vertex is ignored) samples `next`; `mode` is the transport of that subpath.
double pdf_area(const Vertex& v, const Vertex* prev, const Vertex& next, TransportMode mode, double lambda,
                const SceneDisk& disk) {
    const Vec3 wi = direction(v, next);
    if (v.type == VertexType::Camera) {
        Vec2 r;
        double cos_theta = 0;
        return v.pinhole->raster(next.si.p, &r, &cos_theta) ? to_area(v.pinhole->pdf_dir(cos_theta), v, next) : 0.0;
    }
    if (v.type == VertexType::Light) {
        if (v.infinite) return to_area(disk.pdf(), v, next);
        if (delta_position(*v.light)) return to_area(kInv4Pi, v, next);
        const double c = dot(v.si.n, wi);
        return c > 0 ? to_area(c * kInvPi, v, next) : 0.0;
    }
    if (v.type != VertexType::Surface || !v.bsdf || !prev) return 0;
    const Vec3 wo = direction(v, *prev);
    const BSDFContext ctx{lambda, mode};
    return to_area(v.bsdf->pdf(ctx, v.si.to_local(wo), v.si.to_local(wi)), v, next);
}

// Density of choosing light vertex `v` (on v.light) as the start of a light subpath: of its
// point (area measure) or, at infinity, of its direction (solid angle).
double light_origin_pdf(const Scene& scene, const Vertex& v) {
    const Light& light = *v.light;
    const double pmf = scene.light_sampler().pmf(&light);
    if (v.infinite) return pmf * light.pdf_li({}, Vec3(), Vec3(), v.dir);
    if (delta_position(light)) return pmf;
    return light.shape() ? pmf / light.shape()->area() : 0.0;
}

// Adjoint BSDF correction for shading normals (Veach's thesis, Sec. 5.3): in Importance mode
// the throughput must use |wo.ng| |wi.ns| / ... swapped; 1 where ns = ng.
double shading_correction(const SurfaceInteraction& si, const Vec3& wo, const Vec3& wi) {
    const double num = std::abs(dot(wo, si.n)) * std::abs(dot(wi, si.ng));
    const double den = std::abs(dot(wo, si.ng)) * std::abs(dot(wi, si.n));
    return den > 0 ? num / den : 0.0;
}

/// Where a camera subpath escaped the scene (for lights at infinity).
struct Escape {
    bool escaped = false;
    Vec3 d;
    double beta = 0;
    double pdf_dir = 0;  // solid-angle density of d at the last vertex (0 after a delta lobe)
};

// Extends `path` (holding its first vertex) by BSDF sampling until `max_vertices`, absorption
// or roulette. `pdf_dir` is the density of `ray.d` at the first vertex.
void random_walk(const Scene& scene, Ray ray, Sampler& sampler, double lambda, double beta, double pdf_dir,
                 size_t max_vertices, int rr_depth, TransportMode mode, std::vector<Vertex>& path, Escape* escape) {
    const BSDFContext ctx{lambda, mode};
    const BSDFContext ctx_rev{lambda, mode == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance};
    MediumStack media;
    double eta_scale = 1;
    while (path.size() < max_vertices) {
        SurfaceInteraction si;
        if (!scene.intersect(ray, &si)) {
            if (escape) *escape = {true, ray.d, beta, pdf_dir};
            break;
        }
        // A light subpath may start inside a dielectric (a light in coloured glass): it finds
        // out when it leaves an interface from the inside with nothing on its stack, and the
        // segment it just travelled lay in that interior. (Camera subpaths start outside.)
        if (mode == TransportMode::Importance && !media.inside() && dot(ray.d, si.ng) > 0) {
            const BSDF* b = si.bsdf();
            if (b && (b->eta(lambda) != 1.0 || b->interior_absorption())) media.cross(b->interior_absorption(), true);
        }
        beta *= media.transmittance(si.t, lambda);
        Vertex v;
        v.si = si;
        v.bsdf = si.bsdf();
        v.light = si.emitter();
        v.beta = beta;
        v.media = media;
        v.pdf_fwd = to_area(pdf_dir, path.back(), v);
        path.push_back(v);
        if (path.size() >= max_vertices || !v.bsdf) break;

        Vertex& cur = path.back();
        const Vec3 wo = si.to_local(si.wo);
        const auto bs = cur.bsdf->sample(ctx, wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || !(bs->weight > 0)) break;
        const Vec3 wi = si.to_world(bs->wi);
        double pdf_rev_dir = 0;
        if (bs->is_delta()) {
            cur.delta = true;
            pdf_dir = 0;
        } else {
            pdf_dir = bs->pdf;
            pdf_rev_dir = cur.bsdf->pdf(ctx_rev, bs->wi, wo);
        }
        beta *= bs->weight;
        if (mode == TransportMode::Importance) beta *= shading_correction(si, si.wo, wi);
        path[path.size() - 2].pdf_rev = to_area(pdf_rev_dir, cur, path[path.size() - 2]);
        if ((bs->lobe & kTransmission) && (bs->eta != 1.0 || cur.bsdf->interior_absorption()))
            media.cross(cur.bsdf->interior_absorption(), dot(si.wo, si.ng) > 0);
        if (mode == TransportMode::Radiance && (bs->lobe & kTransmission) && bs->eta != 1.0) eta_scale *= sqr(bs->eta);
        ray = scene.spawn_ray(si, wi);
        // Roulette after the same number of surface vertices as the path tracer.
        if (int(path.size()) - 1 >= rr_depth) {
            const double q = std::min(0.95, beta * eta_scale);
            if (!(sampler.next_1d() < q)) break;
            beta /= q;
        }
    }
}

// Samples y_0 on a light and walks the light subpath. A finite light gives a point and a
// cosine-weighted (area) or uniform (point, spot) direction; a light at infinity gives a
// direction d towards it (its own sample_li distribution) and a point on the scene disk facing
// d, from which the subpath travels along -d.
void light_subpath(const Scene& scene, const SceneDisk& disk, Sampler& sampler, double lambda, size_t max_vertices,
                   int rr_depth, std::vector<Vertex>& path) {
    path.clear();
    double pmf = 0;
    const Light* light = scene.light_sampler().sample(sampler.next_1d(), &pmf);
    const Vec2 u_pos = sampler.next_2d(), u_dir = sampler.next_2d();
    if (!light || !(pmf > 0) || max_vertices == 0) return;
    Vertex y0;
    y0.type = VertexType::Light;
    y0.light = light;
    if (light->is_infinite()) {
        const auto ls = light->sample_li({disk.center, Vec3()}, u_dir, lambda);
        if (!ls || !(ls->pdf > 0) || !(ls->Le > 0)) return;
        y0.infinite = true;
        y0.dir = ls->wi;
        y0.pdf_fwd = pmf * ls->pdf;
        y0.beta = 1.0 / (pmf * ls->pdf);  // radiance (irradiance) is evaluated per connection
        const Frame f = Frame::from_normal(ls->wi);
        const Vec2 q = warp::square_to_uniform_disk_concentric(u_pos) * disk.radius;
        y0.si.p = disk.center + ls->wi * disk.radius + f.s * q.x + f.t * q.y;
        path.push_back(y0);
        random_walk(scene, Ray{y0.si.p, -ls->wi}, sampler, lambda, ls->Le / (pmf * ls->pdf * disk.pdf()), disk.pdf(),
                    max_vertices, rr_depth, TransportMode::Importance, path, nullptr);
        return;
    }
    double pdf_pos = 1, pdf_dir = 0, le = 0;
    Vec3 w;
    if (delta_position(*light)) {
        if (const auto* pl = dynamic_cast<const PointLight*>(light)) y0.si.p = pl->position();
        else if (const auto* sl = dynamic_cast<const SpotLight*>(light)) y0.si.p = sl->position();
        else return;
        w = warp::square_to_uniform_sphere(u_dir);
        pdf_dir = kInv4Pi;
        le = light->emitted(y0.si.p, Vec3(), w, lambda);
    } else {
        const Shape* shape = light->shape();
        if (!shape) return;
        const ShapeSample ss = shape->sample_area(u_pos);
        pdf_pos = ss.pdf;
        y0.si.p = ss.p;
        y0.si.n = y0.si.ng = ss.n;
        y0.si.shading = Frame::from_normal(ss.n);
        const Vec3 wl = warp::square_to_cosine_hemisphere(u_dir);
        w = y0.si.to_world(wl);
        pdf_dir = warp::square_to_cosine_hemisphere_pdf(wl);
        le = light->le(ss.p, ss.n, w, lambda) * wl.z;
    }
    if (!(pdf_pos > 0)) return;
    y0.pdf_fwd = pmf * pdf_pos;
    y0.beta = 1.0 / (pmf * pdf_pos);  // emission is evaluated per connection (s = 1)
    path.push_back(y0);
    if (!(le > 0) || !(pdf_dir > 0)) return;
    const Ray ray = y0.has_normal() ? scene.spawn_ray(y0.si, w) : Ray{y0.si.p, w};
    random_walk(scene, ray, sampler, lambda, le / (pmf * pdf_pos * pdf_dir), pdf_dir, max_vertices, rr_depth,
                TransportMode::Importance, path, nullptr);
}

double remap0(double x) { return x != 0 ? x : 1.0; }

// Power-heuristic weight of strategy (s, t) among all strategies s' + t' = s + t with t' >= 1
// (Veach's thesis, Sec. 10.2): the ratios of each alternative's density to this one's follow
// from per-vertex forward and reverse densities, recomputed around the connection.
double mis_weight(const Scene& scene, const SceneDisk& disk, const std::vector<Vertex>& cam,
                  const std::vector<Vertex>& lig, int s, int t, double lambda) {
    if (s + t == 2) return 1.0;  // (0, 2) only: light vertex to pinhole, (1, 1), is not taken
    thread_local std::vector<double> zr, zf, yr, yf;
    thread_local std::vector<char> zd, yd;
    zr.resize(size_t(t)); zf.resize(size_t(t)); zd.resize(size_t(t));
    yr.resize(size_t(s)); yf.resize(size_t(s)); yd.resize(size_t(s));
    for (int i = 0; i < t; ++i) zr[i] = cam[i].pdf_rev, zf[i] = cam[i].pdf_fwd, zd[i] = cam[i].delta;
    for (int i = 0; i < s; ++i) yr[i] = lig[i].pdf_rev, yf[i] = lig[i].pdf_fwd, yd[i] = lig[i].delta;
    const Vertex& z = cam[size_t(t - 1)];
    // The connection's endpoints scatter along the new edge, not along their sampled lobes.
    zd[t - 1] = false;
    bool light_delta = false;
    if (s == 0) {
        // z_{t-1} lies on an area light (or at infinity); seen as a light subpath it is y_0 and
        // emits to z_{t-2}.
        Vertex as_light = z;
        as_light.type = VertexType::Light;
        zr[t - 1] = light_origin_pdf(scene, z);
        zr[t - 2] = pdf_area(as_light, nullptr, cam[size_t(t - 2)], TransportMode::Importance, lambda, disk);
    } else {
        const Vertex& y = lig[size_t(s - 1)];
        const Vertex* zp = t >= 2 ? &cam[size_t(t - 2)] : nullptr;
        yd[s - 1] = false;
        light_delta = delta_origin(*lig[0].light);
        if (t >= 2) {
            zr[t - 1] = pdf_area(y, s >= 2 ? &lig[size_t(s - 2)] : nullptr, z, TransportMode::Importance, lambda, disk);
            zr[t - 2] = pdf_area(z, &y, *zp, TransportMode::Importance, lambda, disk);
        }
        yr[s - 1] = pdf_area(z, zp, y, TransportMode::Radiance, lambda, disk);  // t = 1: the pinhole's density
        if (s >= 2) yr[s - 2] = pdf_area(y, &z, lig[size_t(s - 2)], TransportMode::Radiance, lambda, disk);
    }
    double sum = 0, r = 1;
    // Camera vertices handed to the light subpath: strategies (s + t - i, i), i >= 1 (the
    // pinhole z_0 cannot be hit, so t' = 0 does not exist).
    for (int i = t - 1; i >= 1; --i) {
        r *= remap0(zr[i]) / remap0(zf[i]);
        if (!zd[i] && !zd[i - 1]) sum += r * r;
    }
    r = 1;
    // Light vertices handed to the camera subpath: strategies (i, s + t - i), i < s.
    for (int i = s - 1; i >= 0; --i) {
        r *= remap0(yr[i]) / remap0(yf[i]);
        const bool prev_delta = i > 0 ? yd[i - 1] != 0 : light_delta;
        if (!yd[i] && !prev_delta) sum += r * r;
    }
    return 1.0 / (1.0 + sum);
}

// Unweighted contribution of connecting light vertex y_{s-1} (s >= 1) with camera vertex z_{t-1}.
double connect(const Scene& scene, const std::vector<Vertex>& cam, const std::vector<Vertex>& lig, int s, int t,
               double lambda) {
    const Vertex& z = cam[size_t(t - 1)];
    const Vertex& y = lig[size_t(s - 1)];
    if (!z.connectible() || !y.connectible()) return 0;
    if (y.infinite) {
        // A light at infinity: the "edge" is the direction y.dir; its geometry term is the
        // cosine at z alone. The shadow ray must escape; a camera vertex inside an absorbing
        // medium cannot see the sky without crossing the medium's boundary, which occludes it.
        const double fz = z.bsdf->eval({lambda, TransportMode::Radiance}, z.si.to_local(z.si.wo), z.si.to_local(y.dir)) *
                          std::abs(dot(z.si.n, y.dir));
        const double c = z.beta * fz * y.light->emitted(Vec3(), Vec3(), -y.dir, lambda) * y.beta;
        if (!(c > 0) || scene.occluded(scene.spawn_ray(z.si, y.dir))) return 0;
        return c;
    }
    Vec3 d = y.si.p - z.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return 0;
    const double dist = std::sqrt(d2);
    d /= dist;
    const double fz = z.bsdf->eval({lambda, TransportMode::Radiance}, z.si.to_local(z.si.wo), z.si.to_local(d)) *
                      std::abs(dot(z.si.n, d));
    if (!(fz > 0)) return 0;
    double fy;
    if (s == 1) {
        fy = y.has_normal() ? y.light->le(y.si.p, y.si.n, -d, lambda) * std::abs(dot(y.si.n, d))
                            : y.light->emitted(y.si.p, Vec3(), -d, lambda);
    } else {
        fy = y.bsdf->eval({lambda, TransportMode::Importance}, y.si.to_local(y.si.wo), y.si.to_local(-d)) *
             std::abs(dot(y.si.n, d)) * shading_correction(y.si, y.si.wo, -d);
    }
    double c = z.beta * fz * fy * y.beta / d2;
    if (!(c > 0)) return 0;
    // The edge lies in one medium: z's, or the one behind z's interface when it refracts.
    MediumStack media = z.media;
    if (dot(z.si.wo, z.si.ng) * dot(d, z.si.ng) < 0 && (z.bsdf->eta(lambda) != 1.0 || z.bsdf->interior_absorption()))
        media.cross(z.bsdf->interior_absorption(), dot(z.si.wo, z.si.ng) > 0);
    c *= media.transmittance(dist, lambda);
    if (scene.occluded(scene.spawn_ray_to(z.si, y.si.p))) return 0;
    return c;
}

// Unweighted contribution of the light-tracing strategy t = 1: light vertex y_{s-1} (s >= 2)
// seen by the pinhole at raster position `raster`. W_e cos(theta) / d^2 stands for the camera's
// factor of the connection, as f |cos| / d^2 does for a surface.
double connect_camera(const Scene& scene, const Vertex& z0, const Vertex& y, double lambda, Vec2* raster) {
    if (!y.connectible() || y.type != VertexType::Surface) return 0;
    double cos_theta = 0;
    if (!z0.pinhole->raster(y.si.p, raster, &cos_theta)) return 0;
    Vec3 d = z0.si.p - y.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return 0;
    const double dist = std::sqrt(d2);
    d /= dist;
    const double fy = y.bsdf->eval({lambda, TransportMode::Importance}, y.si.to_local(y.si.wo), y.si.to_local(d)) *
                      std::abs(dot(y.si.n, d)) * shading_correction(y.si, y.si.wo, d);
    double c = y.beta * fy * z0.pinhole->importance(cos_theta) * cos_theta / d2;
    if (!(c > 0)) return 0;
    // The edge lies in y's medium, or the one behind y's interface when it refracts.
    MediumStack media = y.media;
    if (dot(y.si.wo, y.si.ng) * dot(d, y.si.ng) < 0 && (y.bsdf->eta(lambda) != 1.0 || y.bsdf->interior_absorption()))
        media.cross(y.bsdf->interior_absorption(), dot(y.si.wo, y.si.ng) > 0);
    c *= media.transmittance(dist, lambda);
    if (scene.occluded(scene.spawn_ray_to(y.si, z0.si.p))) return 0;
    return c;
}

}  // namespace

int BdptIntegrator::max_layer_depth() const {
    return m_settings.max_depth > 0 ? std::min(m_settings.max_depth, kMaxLayerDepth) : kMaxLayerDepth;
}

int BdptIntegrator::layer_of(int s, int t) const {
    // Lengths k = 1, 2, ... in order; within one, s = 0 .. k (t = k + 1 - s >= 1), without (1, 1).
    int index = 1;
    for (int k = 1; k <= max_layer_depth(); ++k)
        for (int si = 0; si <= k; ++si) {
            if (si == 1 && k == 1) continue;
            if (si == s && k + 1 - si == t) return index;
            ++index;
        }
    return -1;
}

std::vector<std::string> BdptIntegrator::layer_names() const {
    std::vector<std::string> names;
    if (!m_layers) return names;
    for (int k = 1; k <= max_layer_depth(); ++k)
        for (int s = 0; s <= k; ++s) {
            const int t = k + 1 - s;
            if (s == 1 && t == 1) continue;
            names.push_back("d" + std::to_string(k) + "_s" + std::to_string(s) + "_t" + std::to_string(t));
        }
    return names;
}

void BdptIntegrator::prepare(const Scene& /*scene*/, const FilmSpec& film, const RenderOptions& options) const {
    m_window = film;
    m_prepared = true;
    m_layers = options.debug_layers;
}

double BdptIntegrator::li(const Ray&, const Scene&, Sampler&, double) const {
    throw std::logic_error("bdpt splats its light-tracing strategy onto the film: render it with render()");
}

double BdptIntegrator::li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                                SplatList& splats) const {
    thread_counters().paths++;
    const double lambda = cs.lambda;
    const int md = m_settings.max_depth;
    const PerspectiveCamera& camera = *scene.camera();
    const Pinhole pinhole(camera, m_prepared ? m_window : camera.film());
    // Debug layers: each strategy's weighted contribution, at the pixel it reaches.
    const auto record = [&](int s, int t, double c, const Vec2& raster) {
        if (!m_layers) return;
        const int layer = layer_of(s, t);
        if (layer > 0 && c > 0) splats.push_back({raster, radiance_to_xyz(c, lambda, cs.pdf_lambda), layer});
    };

    thread_local std::vector<Vertex> cam, lig;
    cam.clear();
    Vertex z0;
    z0.type = VertexType::Camera;
    z0.si.p = ray.o;
    z0.beta = 1;
    z0.pinhole = &pinhole;
    cam.push_back(z0);
    Escape esc;
    // max_depth counts segments: t <= max_depth + 1 (s = 0) and s <= max_depth (t = 1).
    const size_t cam_max = md < 0 ? size_t(kUnboundedVertices) : size_t(md + 1);
    const size_t light_max = md < 0 ? size_t(kUnboundedVertices) : size_t(md);
    const double pdf_primary = pinhole.pdf_dir(dot(ray.d, camera.forward()));
    random_walk(scene, ray, sampler, lambda, 1.0, pdf_primary, cam_max, m_settings.rr_depth, TransportMode::Radiance,
                cam, &esc);
    const SceneDisk disk(scene.bounds());
    light_subpath(scene, disk, sampler, lambda, light_max, m_settings.rr_depth, lig);

    double L = 0;
    const int nc = int(cam.size()), nl = int(lig.size());
    for (int t = 2; t <= nc; ++t) {
        const Vertex& z = cam[size_t(t - 1)];
        // s = 0: the camera subpath ends on an area light.
        if (z.light && !(m_settings.hide_emitters && t == 2)) {
            const double le = z.light->le(z.si.p, z.si.n, z.si.wo, lambda);
            if (le > 0) {
                const double c = z.beta * le * mis_weight(scene, disk, cam, lig, 0, t, lambda);
                L += c;
                record(0, t, c, cs.raster);
            }
        }
        for (int s = 1; s <= nl; ++s) {
            if (md >= 0 && s + t - 1 > md) break;
            double c = connect(scene, cam, lig, s, t, lambda);
            if (c > 0) {
                c *= mis_weight(scene, disk, cam, lig, s, t, lambda);
                L += c;
                record(s, t, c, cs.raster);
            }
        }
    }
    // t = 1: light tracing. Each light vertex seen by the pinhole lands on its own pixel.
    for (int s = 2; s <= nl; ++s) {
        if (md >= 0 && s > md) break;
        Vec2 raster;
        double c = connect_camera(scene, cam[0], lig[size_t(s - 1)], lambda, &raster);
        if (!(c > 0)) continue;
        c *= mis_weight(scene, disk, cam, lig, s, 1, lambda);
        if (c > 0 && cs.pdf_lambda > 0) splats.push_back({raster, radiance_to_xyz(c, lambda, cs.pdf_lambda), 0});
        record(s, 1, c, raster);
    }
    // s = 0 at infinity: the camera subpath escaped; its end is a vertex at infinity on each
    // light there, weighted against every strategy that could have built the same path.
    if (esc.escaped && !(m_settings.hide_emitters && nc == 1)) {
        Vertex end;
        end.type = VertexType::Surface;
        end.infinite = true;
        end.dir = esc.d;
        end.beta = esc.beta;
        end.pdf_fwd = esc.pdf_dir;
        for (const Light* light : scene.infinite_lights()) {
            const double le = light->le_escaped(esc.d, lambda);
            if (!(le > 0)) continue;
            end.light = light;
            cam.push_back(end);
            const double c = esc.beta * le * mis_weight(scene, disk, cam, lig, 0, nc + 1, lambda);
            cam.pop_back();
            L += c;
            record(0, nc + 1, c, cs.raster);
        }
    }
    return L;
}

}  // namespace snell
