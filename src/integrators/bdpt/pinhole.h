#pragma once
// BDPT's camera vertex z_0: where light tracing (t = 1) lands on the film and how densely
// camera rays cover directions.
#include "camera/camera.h"

namespace snell::bdpt {

/// The pinhole z_0 as a vertex. Camera rays are spread uniformly over the output window of
/// the image plane (at unit distance, area A), so a ray at angle theta to the optical axis has
/// solid-angle density 1 / (A cos^3 theta); the importance of the window that makes light
/// tracing estimate the same pixel means is W_e = 1 / (A cos^4 theta) (Veach's thesis,
/// Sec. 10.3.4; pbrt-v3 Sec. 16.1 uses the whole film where we use the crop window).
struct Pinhole {
    const PerspectiveCamera* camera = nullptr;
    FilmSpec window;
    double area = 0;  // A

    Pinhole(const PerspectiveCamera& cam, const FilmSpec& spec)
        : camera(&cam),
          window(spec),
          area(cam.pixel_plane_area() * double(spec.out_width()) * double(spec.out_height())) {}
    /// Raster position (full film) at which p is seen, when a pixel filter of the output
    /// window covers it (the window grown by the filter margin, where camera samples land too).
    bool raster(const Vec3& p, Vec2* r, double* cos_theta) const {
        if (!camera->raster_of(p, r, cos_theta, window.filter_margin())) return false;
        const Vec2 o = window.sample_origin(), e = window.sample_extent();
        return r->x >= o.x && r->x < o.x + e.x && r->y >= o.y && r->y < o.y + e.y;
    }
    double pdf_dir(double cos_theta) const {
        return cos_theta > 0 ? 1.0 / (area * cos_theta * cos_theta * cos_theta) : 0.0;
    }
    double importance(double cos_theta) const { return cos_theta > 0 ? pdf_dir(cos_theta) / cos_theta : 0.0; }
};

}  // namespace snell::bdpt
