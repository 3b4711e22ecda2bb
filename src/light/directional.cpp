// Directional emitter (:monosp:`directional`), Mitsuba 3 semantics.
//
// | parameter  | type      | meaning                                                      |
// |------------|-----------|--------------------------------------------------------------|
// | irradiance | spectrum  | irradiance on a perpendicular surface, illuminant (def. 1)   |
// | direction  | vector    | direction the light travels in; alternative to to_world      |
// | to_world   | transform | emitter-to-world; light travels along its local +z           |
//
//   <emitter type="directional"> <vector name="direction" x="0" y="-1" z="0"/>
//       <rgb name="irradiance" value="3"/> </emitter>
#include "light/directional.h"

namespace snell {

DirectionalLight::DirectionalLight(const Spectrum& irradiance, const Vec3& direction)
    : m_irradiance(irradiance), m_direction(normalize(direction)) {}

std::optional<LightSample> DirectionalLight::sample_li(const LightSampleContext& ref, const Vec2& /*u*/,
                                                       const SampledWavelengths& wl) const {
    LightSample ls;
    ls.wi = -m_direction;
    ls.p = ref.p + ls.wi * m_sphere.far_distance(ref.p);
    ls.dist = kInfinity;
    ls.Le = m_irradiance.eval(wl);
    ls.pdf = 1;
    ls.delta = true;
    return ls;
}

double DirectionalLight::power() const { return m_irradiance.average() * kPi * sqr(m_sphere.radius); }

SampledSpectrum DirectionalLight::emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3&,
                                          const SampledWavelengths& wl) const {
    return m_irradiance.eval(wl);
}

}  // namespace snell
