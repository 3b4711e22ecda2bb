#pragma once
// Light reflected once off the outside of glass, connected by a manifold walk (issue 26):
// the path x_b, y, x_c with y on a glass shape and x_b, x_c both outside it. BSDF sampling finds
// such a path only when its direction meets the light's small mirror image in the glass, so its
// rare hits were the brightest dots of `glasses` beside the balls (docs/experiments.md,
// "Reflections off the glass"). The straight seed never meets these paths (x_c lies in plain
// sight or behind the glass), so Alg. 1 is run here from a seed of its own: on a caster chosen as
// the surface trials choose (CasterChoice), the point of the shape nearest to where the bisector
// of the directions to x_b and x_c leaves its bounding sphere, the mirror point of a sphere. The
// seed is a function of x_b, x_c and the caster, so Alg. 2's density replays the same walk, and
// the technique is one more MIS technique beside BSDF sampling, with the caster's probability in
// its density. At rough glass y's half vector is drawn from D as Sec. 3.2 draws MNEE's, and NEE
// from y is the third technique: near-specular glass (the demo's droplet, alpha 0.02) shows the
// light as a small bright spot that NEE from y and BSDF sampling both hit rarely.
#include "core/medium_stack.h"
#include "core/sampled_spectrum.h"
#include "core/sampler.h"
#include "geometry/interaction.h"
#include "manifold/light_point.h"
#include "manifold/manifold_technique.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"

namespace snell {

class Light;
class Scene;
class Shape;

/// One reflected connection from x_b.
struct ReflectedConnection {
    bool found = false;
    /// f / p of Alg. 1's last line divided by the caster's probability and by rho (the
    /// connection's), before MIS. The reflection keeps every wavelength (the mirror path is the
    /// same for all).
    SampledSpectrum value;
    double density = 0;   ///< this technique's area density of the path (rho and the caster choice included)
    double pdf_bsdf = 0;  ///< BSDF sampling's, with x_b's direction as the path samples it
    double pdf_nee = 0;   ///< NEE's from a rough y (0 at smooth glass), with x_b's direction the same way
    /// The path: the reflection point y and the light point, on `light` chosen with `pmf`.
    SurfaceInteraction y;
    LightPoint lp;
    const Light* light = nullptr;
    double pmf = 0;
};

class ExteriorReflection {
public:
    ExteriorReflection(const Scene& scene, const MneeSettings& settings) : m_scene(&scene), m_settings(&settings) {}

    /// With probability rho (MneeSettings::exterior_reflections), Alg. 1 for the reflected class:
    /// a light point drawn as NEE draws it, a caster, the seed on it, the walk, visibility and
    /// the measurement in half-vector space (mnee_connect).
    ReflectedConnection connect(const ManifoldQuery& q, Sampler& sampler) const;

    /// Alg. 2 for the path x_b, y, x_c, x_b in `media_b`: the solution density times rho and the
    /// caster's probability where the seed built from x_b, x_c and y's shape walks to y, else 0 (also for
    /// paths outside the class, and from inside glass, where connect() makes none).
    /// `p_others`: the other techniques' density of the path; where it dwarfs the density's bound
    /// (mis_cutoff, as connect() cuts), 0 without the walk.
    double density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const MediumStack& media_b,
                   const SurfaceInteraction& y, const Light& light, double pmf, const Vec3& xc, const Vec3& nc,
                   double lambda, double p_others = 0) const;

    /// The class: y on a manifold interface (smooth or rough), x_b and x_c on its outside (its
    /// normal's side).
    static bool in_class(const Vec3& xb, const SurfaceInteraction& y, const Vec3& xc, double lambda);

    /// Whether the connection is made in `scene`: rho > 0 and the scene has glass (without it no
    /// sampler dimension is drawn, so that `mnee` stays what it was sample for sample).
    static bool made(const Scene& scene, const MneeSettings& settings);

private:
    /// The seed vertex on `caster` for x_b and x_c (reflecting), or false where there is none or
    /// x_b's BSDF gives its direction nothing.
    bool seed(const Shape& caster, const SurfaceInteraction& xb, const BSDF& bsdf_b, const Vec3& xc, double lambda,
              ManifoldVertex* v) const;

    const Scene* m_scene;
    const MneeSettings* m_settings;
};

}  // namespace snell
