#pragma once
// A vertex of the specular (or rough) chain between the shading point x_b and the light point
// x_c, with the local differential geometry the manifold walk needs (paper Sec. 3.4).
#include "core/vector.h"
#include "geometry/interaction.h"
#include "manifold/mat2.h"

namespace snell {

class Shape;
class BSDF;

/// Reference direction from which every constraint frame is built: s = normalize(a - n (n.a)).
/// It is fixed for the whole scene, so the frame is a smooth function of the surface point
/// alone (consistent from sample to sample, no per-triangle jumps that would make rough
/// interfaces blocky); it is singular only where n = ±a, a set of measure zero.
inline Vec3 constraint_frame_reference() { return normalize(Vec3(0.5366, 0.6331, 0.5577)); }

struct ManifoldVertex {
    Vec3 p;                           ///< position
    Vec3 n;                           ///< unit shading normal
    Vec3 ng;                          ///< unit geometric normal (outward side of the shape)
    Vec3 dp_ds, dp_dt;                ///< orthonormal basis of the tangent plane: vertex displacements are
                                      ///< p + dp_ds * a + dp_dt * b, so (a, b) measure area
    Vec3 dn_ds, dn_dt;                ///< derivative of n along dp_ds and dp_dt (shape operator)
    Vec3 s, t;                        ///< constraint frame: s = normalize(a - n (n.a)), t = n x s
    Vec3 ds_ds, ds_dt, dt_ds, dt_dt;  ///< frame derivatives along dp_ds and dp_dt
    double eta = 1;                   ///< IOR inside / outside at the path's wavelength (1: reflection only)
    Vec2 h_target;                    ///< target tangential half vector (0,0) for specular vertices
    /// Rough vertices (has_unit_slope): the drawn microfacet normal as a slope of the unit
    /// roughness distribution. h_target is that slope stretched by the roughness where the vertex
    /// lies, re-read at every projection, so a roughness texture acts where the converged vertex
    /// lies (issue 11) and p_dH(h) = D(h) holds with that vertex's D (see half_vectors.h).
    Vec2 unit_slope;
    bool has_unit_slope = false;
    bool reflect = false;  ///< the chain asks this vertex to reflect (else to refract)
    const Shape* shape = nullptr;
    const BSDF* bsdf = nullptr;
    SurfaceInteraction si;  ///< full hit record at p

    /// Builds the vertex from a surface hit; `eta` is the interface's relative IOR.
    static ManifoldVertex from_interaction(const SurfaceInteraction& si, double eta);
    /// The same in place, from the hit already in `si`: every field but the chain's own
    /// (h_target, unit_slope, has_unit_slope, reflect) is written. A walk's projection builds
    /// its vertex this way at every iteration, without copying the hit record or the vertex.
    void derive_from_si(double eta);
    /// Displaced (unprojected) position for tangent offsets (a, b).
    Vec3 offset(const Vec2& ab) const { return p + dp_ds * ab.x + dp_dt * ab.y; }
};

/// Generalised half vector at a vertex for unit directions wi, wo pointing away from it
/// (paper Fig. 2): h = ±(eta_a wi + eta_b wo) / |.|, with eta_a, eta_b the IORs on the sides
/// of wi and wo; for reflection outside it is the usual (wi + wo)/|.|. The sign (see
/// half_vector_orientation) puts h on the side of n for every admissible configuration.
Vec3 generalized_half_vector(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo);
/// +1 or -1: orientation of the generalised half vector for the sides wi and wo lie on.
double half_vector_orientation(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo);

}  // namespace snell
