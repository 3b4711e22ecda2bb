// Constant environment emitter (:monosp:`constant`), Mitsuba 3 semantics.
//
// | parameter | type     | meaning                                              |
// |-----------|----------|------------------------------------------------------|
// | radiance  | spectrum | emitted radiance, upsampled as an illuminant (def. 1) |
//
//   <emitter type="constant"> <rgb name="radiance" value="0.5"/> </emitter>
#include "light/constant.h"

#include "core/warp.h"

namespace snell {

ConstantLight::ConstantLight(const Spectrum& radiance) : m_radiance(radiance) {}

std::optional<LightSample> ConstantLight::sample_li(const LightSampleContext& ref, const Vec2& u,
                                                    const SampledWavelengths& wl) const {
    LightSample ls;
    ls.wi = warp::square_to_uniform_sphere(u);
    ls.p = ref.p + ls.wi * m_sphere.far_distance(ref.p);
    ls.dist = kInfinity;
    ls.Le = m_radiance.eval(wl);
    ls.pdf = warp::square_to_uniform_sphere_pdf();
    return ls;
}

double ConstantLight::pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const {
    return warp::square_to_uniform_sphere_pdf();
}

SampledSpectrum ConstantLight::le_escaped(const Vec3& /*d*/, const SampledWavelengths& wl) const {
    return m_radiance.eval(wl);
}

double ConstantLight::power() const { return m_radiance.average() * 4 * kPi * kPi * sqr(m_sphere.radius); }

}  // namespace snell
