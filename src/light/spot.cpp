// Spot emitter (:monosp:`spot`), Mitsuba 3 semantics.
//
// | parameter    | type      | meaning                                                     |
// |--------------|-----------|-------------------------------------------------------------|
// | intensity    | spectrum  | peak radiant intensity (W/sr), illuminant (default 1)       |
// | cutoff_angle | float     | degrees beyond which the light is black (default 20)        |
// | beam_width   | float     | degrees of the full-intensity core (default 3/4 cutoff)     |
// | to_world     | transform | emitter-to-world; the light shines along its local +z       |
// | texture      | texture   | projected along the beam, across the cutoff cone (optional) |
//
//   <emitter type="spot"> <transform name="to_world"> <lookat origin="1,1,1" target="1,2,1"/>
//       </transform> </emitter>
#include "light/spot.h"

#include "light/texture_emission.h"

namespace snell {

SpotLight::SpotLight(const Spectrum& intensity, const Transform& to_world, double cutoff_angle_deg,
                     double beam_width_deg, TextureRef texture)
    : m_intensity(intensity),
      m_texture(std::move(texture)),
      m_to_world(to_world),
      m_to_local(to_world.inverse()),
      m_position(to_world.point(Vec3(0, 0, 0))),
      m_cutoff(cutoff_angle_deg * kPi / 180),
      m_beam(beam_width_deg * kPi / 180),
      m_cos_cutoff(std::cos(m_cutoff)),
      m_cos_beam(std::cos(m_beam)) {}

double SpotLight::falloff(const Vec3& w_world) const {
    const Vec3 local = normalize(m_to_local.vector(w_world));
    const double cos_theta = local.z;
    if (!(cos_theta > m_cos_cutoff)) return 0.0;
    if (cos_theta >= m_cos_beam) return 1.0;
    // Linear ramp in angle across the transition band.
    return (m_cutoff - std::acos(clamp(cos_theta, -1.0, 1.0))) / (m_cutoff - m_beam);
}

SampledSpectrum SpotLight::intensity(const Vec3& w_world, const SampledWavelengths& wl) const {
    const double f = falloff(w_world);
    if (!(f > 0)) return {};
    SampledSpectrum I = m_intensity.eval(wl) * f;
    if (m_texture) {
        // The texture spans the cutoff cone's tangent plane: uv = 1/2 at the axis, 0 and 1 at
        // tan(theta) = tan(cutoff) along local x and y.
        const Vec3 l = normalize(m_to_local.vector(w_world));
        const double k = 0.5 / (l.z * std::tan(m_cutoff));
        SurfaceInteraction si;
        si.p = m_position;
        si.uv = Vec2(0.5 + l.x * k, 0.5 + l.y * k);
        I *= texture_emission(*m_texture, si, wl);
    }
    return I;
}

std::optional<LightSample> SpotLight::sample_li(const LightSampleContext& ref, const Vec2& /*u*/,
                                                const SampledWavelengths& wl) const {
    return sample_at_position(m_position, ref, wl);
}

double SpotLight::power() const {
    // 2 pi [ (1 - cos b) + int_b^c (c - t) / (c - b) sin t dt ] with beam b and cutoff c, where
    // int_b^c (c - t) sin t dt = [-(c - t) cos t - sin t]_b^c = (c - b) cos b + sin b - sin c.
    double ramp = 0;
    if (m_cutoff > m_beam)
        ramp = ((m_cutoff - m_beam) * m_cos_beam + std::sin(m_beam) - std::sin(m_cutoff)) / (m_cutoff - m_beam);
    // A texture's mean stands for its mean over the beam (light selection only).
    return 2 * kPi * ((1 - m_cos_beam) + ramp) * m_intensity.average() * (m_texture ? m_texture->mean() : 1.0);
}

SampledSpectrum SpotLight::emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3& w,
                                   const SampledWavelengths& wl) const {
    return intensity(w, wl);
}

}  // namespace snell
