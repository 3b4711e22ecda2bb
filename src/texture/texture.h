#pragma once
// Textures (Mitsuba's <texture> plugins): BSDF parameters that vary over a surface, looked up at
// a surface point. One interface serves colours and scalars, as in Mitsuba: eval() gives the
// spectral value at a path's wavelengths, eval_float() a scalar (a colour's luminance), eval_rgb()
// the stored triple (normal maps).
#include <memory>
#include <utility>

#include "core/object.h"
#include "core/sampled_spectrum.h"
#include "core/spectrum.h"
#include "core/transform.h"
#include "geometry/interaction.h"

namespace snell {

class Texture : public Object {
public:
    virtual SampledSpectrum eval(const SurfaceInteraction& si, const SampledWavelengths& wl) const = 0;
    virtual double eval_float(const SurfaceInteraction& si) const = 0;
    /// The linear RGB triple (raw data for normal maps); greys repeat their value.
    virtual RGB eval_rgb(const SurfaceInteraction& si) const {
        const double v = eval_float(si);
        return RGB(v, v, v);
    }
    /// (d/du, d/dv) of eval_float at si's uv (bump maps); 0 where the texture is piecewise
    /// constant.
    virtual Vec2 eval_float_grad(const SurfaceInteraction& /*si*/) const { return Vec2(0, 0); }
    /// Mean of eval_float over the uv square [0, 1]^2.
    virtual double mean() const = 0;
    /// Bounds of eval_float over every uv (parameter range checks: alpha, weights, opacity).
    virtual double min_value() const = 0;
    virtual double max_value() const = 0;
    /// The same value everywhere (BSDFs keep their constant fast paths).
    virtual bool is_constant() const { return false; }
    /// Texels along u and v (1 x 1 for procedural textures): a projector's aspect ratio.
    virtual std::pair<int, int> resolution() const { return {1, 1}; }
};

using TextureRef = std::shared_ptr<const Texture>;

/// Mitsuba's wrap modes: where a texel index outside [0, n) reads.
enum class WrapMode { Repeat, Mirror, Clamp };
inline int wrap_index(int i, int n, WrapMode w) {
    switch (w) {
        case WrapMode::Clamp:
            return i < 0 ? 0 : (i >= n ? n - 1 : i);
        case WrapMode::Mirror: {
            const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
            return m < n ? m : 2 * n - 1 - m;
        }
        case WrapMode::Repeat:
        default:
            return ((i % n) + n) % n;
    }
}

/// Mitsuba's `to_uv`: a 2D affine map of (u, v); a 4x4 transform from the file acts on (u, v, 0).
inline Vec2 transform_uv(const Transform& to_uv, const Vec2& uv) {
    const Vec3 q = to_uv.point(Vec3(uv.x, uv.y, 0));
    return {q.x, q.y};
}

}  // namespace snell
