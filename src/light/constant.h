#pragma once
#include "core/spectrum.h"
#include "light/light.h"
#include "light/scene_sphere.h"

namespace snell {

/// Mitsuba's `constant` emitter: uniform radiance arriving from every direction at infinity.
class ConstantLight final : public Light {
public:
    explicit ConstantLight(const Spectrum& radiance);

    LightKind kind() const override { return LightKind::Infinite; }
    /// Uniform direction on the sphere: pdf = 1 / (4 pi) sr^-1, dist = inf, p far along wi.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    /// 1 / (4 pi) for every direction.
    double pdf_li(const LightSampleContext& ref, const Vec3& p, const Vec3& n, const Vec3& wi) const override;
    /// The constant radiance, whatever the direction.
    SampledSpectrum le_escaped(const Vec3& d, const SampledWavelengths& wl) const override;
    /// L * 4 pi * pi r^2 (flux into the scene's bounding sphere of radius r).
    double power() const override;
    void preprocess(const Bounds3& scene_bounds) override { m_sphere.set(scene_bounds); }

private:
    Spectrum m_radiance;
    SceneSphere m_sphere;
};

}  // namespace snell
