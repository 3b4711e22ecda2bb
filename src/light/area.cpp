// Area emitter (:monosp:`area`), Mitsuba 3 semantics.
//
// | parameter | type     | meaning                                                    |
// |-----------|----------|------------------------------------------------------------|
// | radiance  | spectrum or texture | emitted radiance: a colour is upsampled as an illuminant |
// |           |                     | (D65 white), a texture as its own spectrum (Mitsuba 3), unbounded |
//
//   <shape type="sphere">
//       <emitter type="area"> <rgb name="radiance" value="10, 10, 10"/> </emitter>
//   </shape>
//
// Emission is one-sided: only towards the side the shape's normal points to.
#include "light/area.h"

#include "light/texture_emission.h"

namespace snell {

AreaLight::AreaLight(const Spectrum& radiance, std::shared_ptr<Shape> shape)
    : m_radiance(radiance), m_shape(std::move(shape)) {}

AreaLight::AreaLight(TextureRef radiance, std::shared_ptr<Shape> shape)
    : m_texture(std::move(radiance)), m_shape(std::move(shape)) {}

SampledSpectrum AreaLight::radiance_at(const Vec3& p, const Vec3& n, const Vec2& uv,
                                       const SampledWavelengths& wl) const {
    if (!m_texture) return m_radiance.eval(wl);
    // The texture reads the emitter's own surface coordinates (Mitsuba's si.uv on the light).
    SurfaceInteraction si;
    si.p = p;
    si.n = si.ng = n;
    si.uv = uv;
    return texture_emission(*m_texture, si, wl);
}

std::optional<LightSample> AreaLight::sample_li(const LightSampleContext& ref, const Vec2& u,
                                                const SampledWavelengths& wl) const {
    const std::optional<ShapeSample> ss = m_shape->sample_from(ref.p, u);
    if (!ss || !(ss->pdf > 0)) return std::nullopt;
    Vec3 d = ss->p - ref.p;
    const double dist2 = length_squared(d);
    if (!(dist2 > 0)) return std::nullopt;
    const double dist = std::sqrt(dist2);
    d /= dist;
    // One-sided emission: the light must face the reference point.
    const double cos_light = -dot(ss->n, d);
    if (!(cos_light > 0)) return std::nullopt;
    LightSample ls;
    ls.p = ss->p;
    ls.n = ss->n;
    ls.wi = d;
    ls.dist = dist;
    ls.uv = ss->uv;
    if (ss->p_error >= 0) {
        ls.p_error = ss->p_error;
    } else {
        SurfaceInteraction anywhere;  // no triangle: the bound for any point of the shape
        anywhere.prim = ~0u;
        ls.p_error = m_shape->position_error(anywhere);
    }
    ls.Le = radiance_at(ss->p, ss->n, ss->uv, wl);
    ls.pdf = ss->pdf;
    // Solid angle -> area: d(omega) = |cos_light| dA / dist^2.
    ls.pdf_area = ss->pdf * cos_light / dist2;
    ls.delta = false;
    return ls;
}

double AreaLight::pdf_li(const LightSampleContext& ref, const Vec3& p, const Vec3& n, const Vec3& /*wi*/) const {
    return m_shape->pdf_from(ref.p, p, n);
}

double AreaLight::pdf_point(const Vec3& ref, const Vec3& p, const Vec3& n) const {
    const Vec3 d = p - ref;
    const double dist2 = length_squared(d);
    const double cos_light = -dot(n, d) / std::sqrt(dist2);
    if (!(cos_light > 0)) return 0;  // sample_li's one-sided culling
    return m_shape->pdf_from(ref, p, n) * cos_light / dist2;
}

SampledSpectrum AreaLight::le(const Vec3& p, const Vec3& n, const Vec2& uv, const Vec3& w,
                              const SampledWavelengths& wl) const {
    return dot(n, w) > 0 ? radiance_at(p, n, uv, wl) : SampledSpectrum();
}

double AreaLight::power() const {
    // A texture's mean over uv stands for its mean over the surface (light selection only).
    const double L = m_texture ? m_texture->mean() : m_radiance.average();
    return L * m_shape->area() * kPi;
}

}  // namespace snell
