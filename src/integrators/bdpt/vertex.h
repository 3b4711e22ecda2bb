#pragma once
// BDPT's subpath vertices and the densities that connect them (Veach's thesis, ch. 10): every
// vertex keeps the area density with which its own subpath sampled it (pdf_fwd) and with
// which the opposite subpath would have (pdf_rev); MIS weights are ratios of these.
#include <cmath>

#include "bsdf/bsdf.h"
#include "core/medium_stack.h"
#include "geometry/interaction.h"
#include "integrators/bdpt/pinhole.h"
#include "light/light.h"
#include "light/scene_sphere.h"

namespace snell {
class Scene;
}

namespace snell::bdpt {

enum class VertexType { Camera, Light, Surface };

/// One subpath vertex. Densities are in area measure at this vertex: pdf_fwd as its own
/// subpath sampled it, pdf_rev as the opposite subpath would (0 through delta lobes).
struct Vertex {
    VertexType type = VertexType::Surface;
    SurfaceInteraction si;  // camera: p only; light: p and n (zero for point and spot)
    const BSDF* bsdf = nullptr;
    const Light* light = nullptr;  // light vertex: its light; surface vertex: the shape's emitter
    SampledSpectrum beta;          // throughput of the subpath up to and including this vertex
    bool hero_only = false;        // a dispersive refraction before it: beta is the hero's alone (scaled)
    double pdf_fwd = 0, pdf_rev = 0;
    bool delta = false;                // scattered by a delta lobe on its own subpath
    MediumStack media;                 // medium on the side the subpath arrived from
    const Pinhole* pinhole = nullptr;  // camera vertex only
    // A vertex at infinity (the start of a light subpath from an environment or directional
    // light, or where a camera subpath escapes): `dir` points from the scene towards it, and
    // its densities are solid-angle densities of that direction (Veach's thesis, Sec. 10.3.5).
    bool infinite = false;
    Vec3 dir;

    bool has_normal() const { return length_squared(si.ng) > 0; }
    bool connectible() const { return type != VertexType::Surface || (bsdf && bsdf->is_smooth_sampled()); }
};

inline bool delta_position(const Light& l) {
    return l.kind() == LightKind::Point || l.kind() == LightKind::Spot || l.kind() == LightKind::Projector;
}
// Lights no camera subpath can hit: a delta position, or the directional light's delta direction.
inline bool delta_origin(const Light& l) { return delta_position(l) || l.kind() == LightKind::Directional; }

// Unit direction from vertex `from` towards vertex `to` (which may lie at infinity).
inline Vec3 direction(const Vertex& from, const Vertex& to) {
    if (to.infinite) return to.dir;
    if (from.infinite) return -from.dir;
    return normalize(to.si.p - from.si.p);
}

/// Light subpaths from lights at infinity start on a disk of the scene's bounding-sphere radius
/// R facing the sampled direction: area density 1 / (pi R^2) across the beam.
struct SceneDisk : SceneSphere {
    explicit SceneDisk(const Bounds3& b) { set(b); }
    double pdf() const { return 1.0 / (kPi * radius * radius); }
};

// Solid-angle density at `from` of the direction to `to`, converted to area measure at `to`
// (geometric normal: the area measure of the surface). Towards a vertex at infinity the
// density stays a solid-angle density; from one, `pdf_dir` is the planar density across the
// beam (SceneDisk), projected onto the surface at `to`.
inline double to_area(double pdf_dir, const Vertex& from, const Vertex& to) {
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
double pdf_area(const Vertex& v, const Vertex* prev, const Vertex& next, TransportMode mode,
                const SampledWavelengths& wl, const SceneDisk& disk);

// Density of choosing light vertex `v` (on v.light) as the start of a light subpath: of its
// point (area measure) or, at infinity, of its direction (solid angle).
double light_origin_pdf(const Scene& scene, const Vertex& v);

// Adjoint BSDF correction for shading normals (Veach's thesis, Sec. 5.3): in Importance mode
// the throughput must use |wo.ng| |wi.ns| / ... swapped; 1 where ns = ng.
double shading_correction(const SurfaceInteraction& si, const Vec3& wo, const Vec3& wi);

}  // namespace snell::bdpt
