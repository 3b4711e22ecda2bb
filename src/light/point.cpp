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
    const Vec3 d = m_position - ref.p;
    const double dist2 = length_squared(d);
    if (!(dist2 > 0)) return std::nullopt;
    LightSample ls;
    ls.p = m_position;
    ls.dist = std::sqrt(dist2);
    ls.wi = d / ls.dist;
    ls.Le = m_intensity.eval(wl) / dist2;  // inverse-square law
    ls.pdf = 1;
    ls.delta = true;
    return ls;
}

double PointLight::power() const { return 4 * kPi * m_intensity.average(); }

SampledSpectrum PointLight::emitted(const Vec3&, const Vec3&, const Vec2&, const Vec3& /*w*/,
                                    const SampledWavelengths& wl) const {
    return m_intensity.eval(wl);
}

}  // namespace snell
