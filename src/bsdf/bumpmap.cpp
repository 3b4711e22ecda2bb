#include "bsdf/bumpmap.h"

namespace snell {

Vec3 BumpMapBSDF::local_normal(const BSDFContext& ctx) const {
    const SurfaceInteraction& si = ctx.point();
    const Vec2 g = m_height->eval_float_grad(si) * m_scale;
    const Vec3 dpdu = si.dpdu + si.n * (g.x - dot(si.n, si.dpdu));
    const Vec3 dpdv = si.dpdv + si.n * (g.y - dot(si.n, si.dpdv));
    Vec3 n = cross(dpdu, dpdv);
    if (dot(n, si.ng) < 0) n = -n;
    return si.to_local(n);
}

}  // namespace snell
