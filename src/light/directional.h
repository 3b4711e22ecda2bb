#pragma once
#include "core/spectrum.h"
#include "light/light.h"
#include "light/scene_sphere.h"

namespace snell {

/// Mitsuba's `directional` emitter: a distant source of irradiance E (W / (m^2 nm)) on
/// surfaces perpendicular to its direction of travel.
class DirectionalLight final : public Light {
public:
    /// `direction`: unit direction in which light travels (away from the source).
    DirectionalLight(const Spectrum& irradiance, const Vec3& direction);

    LightKind kind() const override { return LightKind::Directional; }
    /// Delta sample: wi = -direction, Le = E, pdf = 1, dist = inf, p far along wi.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    double pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
    /// E * pi r^2 for the scene's bounding sphere of radius r.
    /// The irradiance (direction-independent: MNEE's far point stands in for the direction).
    SampledSpectrum emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3&,
                            const SampledWavelengths& wl) const override;
    double power() const override;
    void preprocess(const Bounds3& scene_bounds) override { m_sphere.set(scene_bounds); }
    const Vec3& direction() const { return m_direction; }

private:
    Spectrum m_irradiance;
    Vec3 m_direction;
    SceneSphere m_sphere;
};

}  // namespace snell
