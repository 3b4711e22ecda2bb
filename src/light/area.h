#pragma once
#include <memory>

#include "core/spectrum.h"
#include "geometry/shape.h"
#include "light/light.h"
#include "texture/texture.h"

namespace snell {

/// Mitsuba's `area` emitter: radiance leaving the surface of a shape, one-sided, on the side
/// its normal points to (flip_normals on the shape turns it around); uniform, or a texture
/// over the shape's uv. A textured light is sampled by area as an untextured one is.
class AreaLight final : public Light {
public:
    /// `radiance` in W / (m^2 sr nm) at each wavelength. Does not register with the shape;
    /// create_area_light does (Shape::set_emitter).
    AreaLight(const Spectrum& radiance, std::shared_ptr<Shape> shape);
    /// Textured radiance, read at the emitting point's uv (Texture::eval, as Mitsuba 3 does).
    AreaLight(TextureRef radiance, std::shared_ptr<Shape> shape);

    LightKind kind() const override { return LightKind::Area; }
    /// Samples the shape as seen from ref.p (Shape::sample_from: cone sampling for spheres,
    /// area sampling otherwise); pdf in solid angle, pdf_area = pdf * |cos_light| / dist^2.
    /// nullopt when the sampled point faces away from ref (no emission towards it).
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    /// Shape::pdf_from(ref.p, p, n): solid-angle density at ref.
    double pdf_li(const LightSampleContext& ref, const Vec3& p, const Vec3& n, const Vec3& wi) const override;
    /// radiance if dot(n, w) > 0, else 0.
    /// Area density of sample_li's point, zero where the light faces away from ref.
    double pdf_point(const Vec3& ref, const Vec3& p, const Vec3& n) const override;
    SampledSpectrum le(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                       const SampledWavelengths& wl) const override;
    /// Average radiance * area * pi.
    double power() const override;
    const Shape* shape() const override { return m_shape.get(); }
    const Spectrum& radiance() const { return m_radiance; }
    bool is_textured() const { return m_texture != nullptr; }
    bool reads_uv() const override { return is_textured(); }

private:
    SampledSpectrum radiance_at(const Vec3& p, const Vec3& n, const Vec2& uv, const SampledWavelengths& wl) const;

    Spectrum m_radiance;
    TextureRef m_texture;  ///< when set, the radiance (m_radiance unused)
    std::shared_ptr<Shape> m_shape;
};

}  // namespace snell
