#pragma once
#include "core/spectrum.h"
#include "core/transform.h"
#include "light/light.h"
#include "texture/texture.h"

namespace snell {

/// Mitsuba's `projector`: a pinhole that projects an image, the reciprocal of the perspective
/// camera. `irradiance` (a texture, or a colour upsampled as an illuminant) is given on the
/// virtual image plane at unit distance along local +z, which spans the field of view; the
/// intensity along a direction at angle theta to the axis is pi scale E(uv) / cos^3(theta), so
/// that a plane facing the projector at unit distance receives pi scale E (Mitsuba 3's
/// normalisation, which its reference renders follow). Local +x maps to decreasing u and +y to
/// decreasing v (v = 0 is the image's top row), as a camera's raster does.
class ProjectorLight final : public Light {
public:
    /// `tan_half` holds the tangents of half the field of view along local x and y.
    ProjectorLight(const Spectrum& irradiance, TextureRef texture, double scale, const Transform& to_world,
                   const Vec2& tan_half);

    LightKind kind() const override { return LightKind::Projector; }
    /// Delta sample: Le = I(w) / dist^2, pdf = 1; zero (still returned, for MNEE) outside the image.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    double pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override { return 0; }
    double pdf_point(const Vec3&, const Vec3&, const Vec3&) const override { return 1; }
    /// Intensity emitted along w (away from the light).
    SampledSpectrum emitted(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                            const SampledWavelengths& wl) const override;
    /// pi scale mean(E) times the image plane's area (exact for the image's mean).
    double power() const override;
    Vec3 position() const override { return m_position; }

    /// Image coordinates of the local direction d (d.z > 0); false outside the image.
    bool uv_of(const Vec3& d_local, Vec2* uv) const;

private:
    Spectrum m_irradiance;
    TextureRef m_texture;  ///< when set, the irradiance (m_irradiance unused)
    double m_scale;
    Transform m_to_world, m_to_local;
    Vec3 m_position;
    Vec2 m_tan;
};

}  // namespace snell
