#pragma once
#include "core/spectrum.h"
#include "core/transform.h"
#include "light/light.h"
#include "texture/texture.h"

namespace snell {

/// Mitsuba's `spot` emitter: a point source at the origin of `to_world` shining along local
/// +z with intensity I * falloff(theta). Mitsuba 3's profile: 1 inside the beam width, a linear
/// ramp in angle (cutoff - theta) / (cutoff - beam_width) between beam width and cutoff, and 0
/// beyond the cutoff. An optional `texture` is projected along the beam: it multiplies the
/// intensity at uv = 1/2 + (x, y) / (2 z tan(cutoff)) of the local direction (Mitsuba 3).
class SpotLight final : public Light {
public:
    /// Angles in degrees, 0 < beam_width <= cutoff_angle <= 90 (validated by the factory).
    SpotLight(const Spectrum& intensity, const Transform& to_world, double cutoff_angle_deg, double beam_width_deg,
              TextureRef texture = nullptr);

    LightKind kind() const override { return LightKind::Spot; }
    /// Delta sample: Le = I falloff / dist^2, pdf = 1; nullopt outside the cone.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    double pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
    /// Integral of the falloff over the sphere times the average intensity (exact).
    /// Delta position: the light point is always its position (discrete probability 1).
    double pdf_point(const Vec3&, const Vec3&, const Vec3&) const override { return 1; }
    /// Intensity emitted along w (away from the light).
    SampledSpectrum emitted(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                            const SampledWavelengths& wl) const override;
    double power() const override;

    /// Falloff factor in [0, 1] for the unit emission direction `w_world` (away from the light).
    double falloff(const Vec3& w_world) const;
    /// Intensity along unit `w_world` (away from the light): I falloff texture.
    SampledSpectrum intensity(const Vec3& w_world, const SampledWavelengths& wl) const;
    Vec3 position() const override { return m_position; }

private:
    Spectrum m_intensity;
    TextureRef m_texture;  ///< projected along the beam; null for none
    Transform m_to_world, m_to_local;
    Vec3 m_position;
    double m_cutoff, m_beam;  // radians
    double m_cos_cutoff, m_cos_beam;
};

}  // namespace snell
