#pragma once
// Mitsuba's `orthographic` sensor: parallel rays along camera-space +z from the points
// (x, y, near_clip) with x in [-1, 1] and y in [-1/aspect, 1/aspect] (+x to the left, +y up);
// `to_world` scales that window to the visible extent, as in Mitsuba.
#include "camera/camera.h"

namespace snell {

class OrthographicCamera final : public Camera {
public:
    OrthographicCamera(const Transform& to_world, const FilmSpec& film, double near_clip = 1e-2, double far_clip = 1e4)
        : Camera(to_world, film), m_near(near_clip), m_far(far_clip) {}

    Ray generate_ray(const Vec2& raster, const Vec2& u_lens) const override;

private:
    double m_near, m_far;
};

}  // namespace snell
