#pragma once
// Mitsuba's `normalmap`: the shading normal read from an RGB texture (n = 2 rgb - 1 in the
// surface's local frame: x along dp/du, z the normal), the nested BSDF evaluated in that frame.
// The texture is usually a `bitmap` with `raw` true.
#include "bsdf/perturbed_frame.h"
#include "texture/texture.h"

namespace snell {

class NormalMapBSDF final : public PerturbedFrameBSDF {
public:
    NormalMapBSDF(TextureRef normals, std::shared_ptr<const BSDF> nested, Options opt = {})
        : PerturbedFrameBSDF(std::move(nested), opt), m_normals(std::move(normals)) {}

    Vec3 local_normal(const BSDFContext& ctx) const override {
        const RGB c = m_normals->eval_rgb(ctx.point());
        return Vec3(2 * c.r - 1, 2 * c.g - 1, 2 * c.b - 1);
    }

private:
    TextureRef m_normals;
};

}  // namespace snell
