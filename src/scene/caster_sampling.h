#pragma once
// Caster sampling (issue 26): at a reflecting, non-delta vertex, BSDF sampling mixed with
// directions drawn uniformly in the cones that hold the scene's refractive shapes.
//
// Why: where glass focuses a small light onto a floor (a ball on a plane), the light seen from
// the floor through the glass covers much of the glass, so a direction aimed at the glass finds
// the light often, while a cosine-distributed one meets the glass rarely. There the light's
// position is the wrong variable to sample: MNEE's walks from a point on the light mostly fail
// (the floor point is the image of one small part of the light) and its per-sample variance is
// no lower than BSDF sampling's (docs/experiments.md, "Aiming BSDF sampling at the glass").
//
// Where: only where a caster's cone overlaps a light's as seen from the vertex, that is in the
// caster's (soft) shadow, where a focusing glass puts its caustic. Elsewhere, in a room with a
// glass ball say, the light arrives directly and aiming at the glass only takes samples from the
// indirect light (docs/experiments.md, "Caster sampling in the casters' shadows").
//
// It is a one-sample mixture (Veach 1997, Sec. 9.2.4: a technique's density is the mixture's),
// so it adds no MIS technique: every weight that reads BSDF sampling's density at such a vertex
// reads pdf() (NEE's, the emitter hits', MNEE's Alg. 2 densities), and the estimate stays
// unbiased for any choice of cones.
#include <optional>

#include "bsdf/bsdf.h"
#include "geometry/interaction.h"

namespace snell {

class Scene;

class CasterSampling {
public:
    /// Scenes with more refractive shapes than this sample their BSDFs alone (the density is a
    /// sum over the casters, evaluated at every MIS weight).
    static constexpr size_t kMaxCasters = 16;
    /// Scenes with more lights than this (or a bright environment) aim at the casters wherever their
    /// cones reach above the surface, without the shadow test.
    static constexpr size_t kMaxLights = 16;

    /// `probability`: the share of directions aimed at the casters where any applies (0: off).
    CasterSampling(const Scene& scene, double probability);

    /// Whether the mixture samples the direction leaving `si` (reflecting, non-delta BSDF and
    /// at least one caster's cone reaches above its surface and overlaps a light's).
    bool applies(const SurfaceInteraction& si, const BSDF& bsdf) const;
    /// A direction leaving `si` (local frame, like BSDF::sample) and its weight f |cos| / pdf
    /// with pdf the mixture's; uc picks the technique and is reused within it.
    std::optional<BSDFSample> sample(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, double uc,
                                     const Vec2& u) const;
    /// Solid-angle density of sample() producing the local direction wi (BSDF::pdf where the
    /// mixture does not apply).
    double pdf(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, const Vec3& wo,
               const Vec3& wi) const;

private:
    /// A caster seen from a vertex: the unit direction to its sphere's centre and 1 - cos of
    /// the half angle it subtends.
    struct Cone {
        Vec3 axis;
        double one_minus_cos = 0;
    };
    /// Whether a vertex of this BSDF may aim at the casters (reflecting, non-delta).
    bool aims_at(const BSDF& bsdf) const;
    /// The caster cones' part of the density of world direction d leaving si: their average.
    static double cone_pdf(const Cone* cones, size_t n, const Vec3& d);
    /// Caster i seen from si; false where it does not apply (si inside its sphere, the cone
    /// wholly below si's surface, or outside every light's cone).
    bool cone(const SurfaceInteraction& si, size_t i, Cone* out) const;
    /// Whether the cone overlaps that of some light seen from p (true without the shadow test).
    bool overlaps_a_light(const Vec3& p, const Cone& c) const;
    /// The cones that apply at si, written to `cones` (kMaxCasters long); their number.
    size_t applicable(const SurfaceInteraction& si, Cone* cones) const;

    const Scene* m_scene;
    double m_probability;
};

}  // namespace snell
