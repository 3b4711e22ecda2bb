#pragma once
// Mitsuba's `thinlens` sensor: the perspective projection with a finite circular aperture of
// radius `aperture_radius` at the camera's origin, focused on the plane at `focus_distance`
// along the optical axis (pbrt-v4 Sec. 5.2.3). Points on that plane are sharp; the rest blurs.
#include "camera/camera.h"

namespace snell {

class ThinLensCamera final : public PerspectiveCamera {
public:
    ThinLensCamera(const Transform& to_world, double fov_deg, const std::string& fov_axis, const FilmSpec& film,
                   double aperture_radius, double focus_distance, double near_clip = 1e-2, double far_clip = 1e4)
        : PerspectiveCamera(to_world, fov_deg, fov_axis, film, near_clip, far_clip),
          m_aperture(aperture_radius),
          m_focus(focus_distance) {}

    Ray generate_ray(const Vec2& raster, const Vec2& u_lens) const override;
    bool has_lens() const override { return true; }
    /// No light tracing into a finite aperture (BDPT's t = 1 would need lens sampling).
    const PerspectiveCamera* pinhole() const override { return nullptr; }
    double aperture_radius() const { return m_aperture; }
    double focus_distance() const { return m_focus; }

private:
    double m_aperture, m_focus;
};

}  // namespace snell
