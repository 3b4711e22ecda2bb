#include "bsdf/bsdf.h"

#include "core/stats.h"

namespace snell {

namespace {
StatCounter lookups_without_point{"bsdf.lookups_without_point",
                                  "textured BSDF parameters read without a surface point (a bug)"};
}  // namespace

const SurfaceInteraction& BSDFContext::point() const {
    if (si) return *si;
    ++lookups_without_point;
    static const SurfaceInteraction origin{};
    return origin;
}

}  // namespace snell
