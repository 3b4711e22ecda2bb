#pragma once
// Emitter interface. Radiance/intensity values are at the path's wavelengths.
#include <cmath>
#include <optional>

#include "core/object.h"
#include "core/sampled_spectrum.h"
#include "core/vector.h"

namespace snell {

class Shape;

enum class LightKind { Area, Point, Spot, Projector, Directional, Infinite };

/// Reference point for light sampling: position and (optional, zero if none) shading normal.
struct LightSampleContext {
    Vec3 p;
    Vec3 n;  ///< zero vector when unknown/irrelevant
};

struct LightSample {
    Vec3 p;                   ///< point on the light (for directional/infinite: far away along wi)
    Vec3 n;                   ///< light normal at p (zero for point/spot/directional/infinite)
    Vec2 uv;                  ///< surface parameterisation at p (area lights; textured emission)
    Vec3 wi;                  ///< unit direction from the reference point towards the light
    double dist = kInfinity;  ///< distance to p (infinite for directional/infinite lights)
    /// Bound on the rounding error of p on the light's shape (area lights; Shape::position_error):
    /// a shadow ray stops this far short of p, so it does not hit the light itself.
    double p_error = 0;
    /// Incident radiance for area and infinite lights. For delta lights the factor that makes
    /// the estimate f |cos| Le / pdf correct: point/spot intensity / dist^2, directional irradiance.
    SampledSpectrum Le;
    double pdf = 0;       ///< solid-angle density at the reference point (1 for delta lights)
    double pdf_area = 0;  ///< area density of p on the light (area lights; 0 otherwise)
    bool delta = false;   ///< position or direction is a Dirac delta (no MIS with BSDF sampling)
};

class Light : public Object {
public:
    virtual LightKind kind() const = 0;
    bool is_delta() const {
        const LightKind k = kind();
        return k == LightKind::Point || k == LightKind::Spot || k == LightKind::Projector ||
               k == LightKind::Directional;
    }
    bool is_infinite() const { return kind() == LightKind::Infinite || kind() == LightKind::Directional; }

    /// Samples incident illumination at ref. Returns nullopt when nothing can be sampled.
    virtual std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                                 const SampledWavelengths& wl) const = 0;
    /// Solid-angle density that sample_li(ref) returns the point p (normal n) in direction wi.
    /// For infinite lights p and n are ignored. 0 for delta lights.
    virtual double pdf_li(const LightSampleContext& ref, const Vec3& p, const Vec3& n, const Vec3& wi) const = 0;

    /// Whether le() reads uv (a textured radiance). Default true (Shape::reads_uv).
    virtual bool reads_uv() const { return true; }
    /// Area lights: radiance leaving point p (normal n, surface coordinates uv, which a
    /// textured radiance reads) in unit direction w (away from the light).
    virtual SampledSpectrum le(const Vec3& /*p*/, const Vec3& /*n*/, const Vec2& /*uv*/, const Vec3& /*w*/,
                               const SampledWavelengths& /*wl*/) const {
        return {};
    }
    /// Infinite lights: radiance arriving along a ray escaping the scene in unit direction d.
    virtual SampledSpectrum le_escaped(const Vec3& /*d*/, const SampledWavelengths& /*wl*/) const { return {}; }

    /// MNEE (paper Alg. 2, first line): density in area measure with which sample_li(ref)
    /// returns the light point p with normal n, including its culling (0 where sample_li never
    /// returns p). Delta-position lights (point, spot) return 1; lights at infinity 0.
    virtual double pdf_point(const Vec3& /*ref*/, const Vec3& /*p*/, const Vec3& /*n*/) const { return 0; }
    /// MNEE: emission leaving light point p (normal n) along unit direction w: radiance for
    /// area lights, intensity for point and spot lights (the admissible path leaves the light
    /// in a different direction than the seed path, so this is evaluated afresh).
    /// Lights at infinity give the radiance arriving from -w (environment) or, for the
    /// directional light, its irradiance (MNEE turns both into points on a far sphere).
    virtual SampledSpectrum emitted(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                                    const SampledWavelengths& wl) const {
        return is_infinite() ? le_escaped(-w, wl) : le(p, n, uv, w, wl);
    }

    /// Emitted power, averaged over the visible range (for light selection; need not be exact).
    virtual double power() const = 0;
    /// Called once the scene bounds are known (infinite and directional lights need them).
    virtual void preprocess(const Bounds3& /*scene_bounds*/) {}
    /// Lights at a point (point, spot, projector): where they sit.
    virtual Vec3 position() const { return Vec3(); }
    /// The shape of an area light, else nullptr.
    virtual const Shape* shape() const { return nullptr; }

protected:
    /// sample_li of a light at a point (point, spot, projector): the delta sample at `pos` seen
    /// from ref, Le = emitted intensity towards ref / distance^2. A zero Le (outside a cone) is
    /// still returned: MNEE needs the light's position whatever the direction towards ref.
    std::optional<LightSample> sample_at_position(const Vec3& pos, const LightSampleContext& ref,
                                                  const SampledWavelengths& wl) const {
        const Vec3 d = pos - ref.p;
        const double dist2 = length_squared(d);
        if (!(dist2 > 0)) return std::nullopt;
        LightSample ls;
        ls.p = pos;
        ls.dist = std::sqrt(dist2);
        ls.wi = d / ls.dist;
        ls.Le = emitted(pos, Vec3(), Vec2(), -ls.wi, wl) / dist2;  // inverse-square law
        ls.pdf = 1;
        ls.delta = true;
        return ls;
    }
};

}  // namespace snell
