#pragma once
// Mitsuba's `bumpmap`: the surface displaced along its normal by scale * h(u, v) for a height
// texture h, with the normal of the displaced surface from the perturbed tangents
// dp/du + n dh/du and dp/dv + n dh/dv (Blinn 1978, neglecting the derivative of n as Mitsuba
// does), flipped to the side of the geometric normal, and the nested BSDF evaluated in that frame.
#include "bsdf/perturbed_frame.h"
#include "texture/texture.h"

namespace snell {

class BumpMapBSDF final : public PerturbedFrameBSDF {
public:
    BumpMapBSDF(TextureRef height, double scale, std::shared_ptr<const BSDF> nested, Options opt = {})
        : PerturbedFrameBSDF(std::move(nested), opt), m_height(std::move(height)), m_scale(scale) {}

    Vec3 local_normal(const BSDFContext& ctx) const override;

private:
    TextureRef m_height;
    double m_scale;
};

}  // namespace snell
