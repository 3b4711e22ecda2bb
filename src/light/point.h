#pragma once
#include "core/spectrum.h"
#include "light/light.h"

namespace snell {

/// Mitsuba's `point` emitter: isotropic point source of radiant intensity I (W / (sr nm)).
class PointLight final : public Light {
public:
    PointLight(const Spectrum& intensity, const Vec3& position);

    LightKind kind() const override { return LightKind::Point; }
    /// Delta sample: Le = I / dist^2, pdf = 1, delta = true; u is unused.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    /// 0: a delta light cannot be hit by BSDF sampling.
    double pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
    /// 4 pi * average intensity.
    /// Delta position: the light point is always its position (discrete probability 1).
    double pdf_point(const Vec3&, const Vec3&, const Vec3&) const override { return 1; }
    /// Intensity emitted along w (away from the light).
    SampledSpectrum emitted(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                            const SampledWavelengths& wl) const override;
    double power() const override;
    Vec3 position() const override { return m_position; }

private:
    Spectrum m_intensity;
    Vec3 m_position;
};

}  // namespace snell
