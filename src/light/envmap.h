#pragma once
#include <string>
#include <vector>

#include "core/spectrum.h"
#include "core/transform.h"
#include "io/image.h"
#include "light/distribution2d.h"
#include "light/light.h"
#include "light/scene_sphere.h"

namespace snell {

/// Mitsuba's `envmap` emitter: radiance at infinity from a latitude-longitude RGB image.
///
/// Mapping (exactly Mitsuba 3's): in the emitter's local frame +y is up. A local unit
/// direction d has theta = acos(d.y) in [0, pi] and phi = atan2(d.x, -d.z) wrapped into
/// [0, 2 pi); its image coordinates are u = phi / (2 pi) (columns, left to right) and
/// v = theta / pi (rows, top row = +y). Conversely d = (sin t sin p, cos t, -sin t cos p).
/// Image rows 0 and H-1 sit exactly on the poles (v = j / (H - 1)); column i is centred at
/// u = (i + 1/2) / W with periodic wrap; radiance between texel centres is bilinear in RGB.
///
/// Spectra: the interpolated RGB is upsampled with RGBIlluminantTable (white (1,1,1) gives
/// the renderer's white illuminant), then multiplied by `scale`.
///
/// Sampling: a W x H piecewise-constant Distribution2D over (u, v) whose bin values are the
/// exact bin integrals of the bilinear luminance times the bin's mean sin(theta), so every
/// direction with non-zero radiance has non-zero density. Solid-angle pdf =
/// pdf_uv / (2 pi^2 sin theta).
class EnvironmentMap final : public Light {
public:
    /// `image`: linear RGB, at least 2 x 3 texels (Mitsuba's minimum). `to_world` must be a
    /// rotation (the pdf ignores any scaling).
    EnvironmentMap(Image image, double scale, const Transform& to_world);

    LightKind kind() const override { return LightKind::Infinite; }
    /// Importance-sampled direction; dist = inf, p = ref + wi * far distance.
    std::optional<LightSample> sample_li(const LightSampleContext& ref, const Vec2& u,
                                         const SampledWavelengths& wl) const override;
    /// The direction sampling inside sample_li, without radiance: a unit world direction and
    /// its solid-angle density `pdf` (0 when no direction could be produced). Optionally
    /// returns the map coordinates of the sample.
    Vec3 sample_direction(const Vec2& u, double* pdf, Vec2* uv_out = nullptr) const;
    /// Solid-angle density of sample_li producing direction wi (p, n ignored).
    double pdf_li(const LightSampleContext& ref, const Vec3& p, const Vec3& n, const Vec3& wi) const override;
    /// Radiance arriving along a ray that escapes in world direction d.
    SampledSpectrum le_escaped(const Vec3& d, const SampledWavelengths& wl) const override;
    /// pi r^2 * integral over the sphere of the (luminance-based) average radiance.
    double power() const override;
    void preprocess(const Bounds3& scene_bounds) override { m_sphere.set(scene_bounds); }

    /// Local direction -> (u, v) in [0,1)^2 x [0,1] (Mitsuba's convention, see class doc).
    static Vec2 direction_to_uv(const Vec3& d_local);
    /// (u, v) -> unit local direction.
    static Vec3 uv_to_direction(const Vec2& uv);
    /// Bilinearly interpolated (unscaled) RGB at image coordinates uv.
    RGB lookup_rgb(const Vec2& uv) const;

private:
    Image m_image;
    double m_scale;
    Transform m_to_world, m_to_local;
    Distribution2D m_dist;
    double m_luminance_integral = 0;  // integral over the sphere of luminance(L) d(omega)
    SceneSphere m_sphere;
};

}  // namespace snell
