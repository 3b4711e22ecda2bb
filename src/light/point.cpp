// Point emitter (:monosp:`point`), Mitsuba 3 semantics.
//
// | parameter | type      | meaning                                                       |
// |-----------|-----------|---------------------------------------------------------------|
// | intensity | spectrum  | radiant intensity (W/sr), upsampled as an illuminant (def. 1) |
// | position  | point     | location; alternative to to_world                             |
// | to_world  | transform | emitter-to-world transform; the light sits at its origin      |
//
//   <emitter type="point"> <point name="position" x="0" y="2" z="0"/>
//       <rgb name="intensity" value="5"/> </emitter>
#include "light/point.h"

namespace snell {

PointLight::PointLight(const Spectrum& intensity, const Vec3& position)
    : m_intensity(intensity), m_position(position) {}

std::optional<LightSample> PointLight::sample_li(const LightSampleContext& ref, const Vec2& /*u*/,
                                                 const SampledWavelengths& wl) const {
    return sample_at_position(m_position, ref, wl);
}

double PointLight::power() const { return 4 * kPi * m_intensity.average(); }

SampledSpectrum PointLight::emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3& /*w*/,
                                    const SampledWavelengths& wl) const {
    return m_intensity.eval(wl);
}

}  // namespace snell
