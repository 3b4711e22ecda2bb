// Projector emitter (:monosp:`projector`), Mitsuba 3 semantics.
//
// | parameter    | type                | meaning                                                  |
// |--------------|---------------------|----------------------------------------------------------|
// | irradiance   | spectrum or texture | on the image plane at unit distance (default 1)          |
// | scale        | float               | multiplies the irradiance (default 1)                    |
// | fov, fov_axis, focal_length | as the perspective sensor | the image's field of view; its aspect is the texture's |
// | to_world     | transform           | emitter-to-world; it projects along its local +z         |
#include "light/projector.h"

#include "light/texture_emission.h"

#include <cmath>

namespace snell {

ProjectorLight::ProjectorLight(const Spectrum& irradiance, TextureRef texture, double scale, const Transform& to_world,
                               const Vec2& tan_half)
    : m_irradiance(irradiance),
      m_texture(std::move(texture)),
      m_scale(scale),
      m_to_world(to_world),
      m_to_local(to_world.inverse()),
      m_position(to_world.point(Vec3(0, 0, 0))),
      m_tan(tan_half) {}

bool ProjectorLight::uv_of(const Vec3& d, Vec2* uv) const {
    if (!(d.z > 0)) return false;
    const double sx = d.x / (d.z * m_tan.x), sy = d.y / (d.z * m_tan.y);
    *uv = Vec2(0.5 * (1 - sx), 0.5 * (1 - sy));
    return uv->x >= 0 && uv->x <= 1 && uv->y >= 0 && uv->y <= 1;
}

SampledSpectrum ProjectorLight::emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3& w,
                                        const SampledWavelengths& wl) const {
    const Vec3 d = normalize(m_to_local.vector(w));
    Vec2 uv;
    if (!uv_of(d, &uv)) return {};
    SampledSpectrum E;
    if (m_texture) {
        SurfaceInteraction si;
        si.p = m_position;
        si.uv = uv;
        E = texture_emission(*m_texture, si, wl);
    } else {
        E = m_irradiance.eval(wl);
    }
    // The solid angle of an image-plane patch dA at unit depth is cos^3(theta) dA: dividing by
    // cos^3 makes the irradiance on that plane E itself (times pi scale, as Mitsuba 3 has it).
    const double c = d.z;
    return E * (kPi * m_scale / (c * c * c));
}

std::optional<LightSample> ProjectorLight::sample_li(const LightSampleContext& ref, const Vec2& /*u*/,
                                                     const SampledWavelengths& wl) const {
    return sample_at_position(m_position, ref, wl);
}

double ProjectorLight::power() const {
    // int I dw = pi scale int E dA over the unit-depth image plane (dw = cos^3 dA there).
    const double E = m_texture ? m_texture->mean() : m_irradiance.average();
    return kPi * m_scale * E * 4 * m_tan.x * m_tan.y;
}

}  // namespace snell
