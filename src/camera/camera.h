#pragma once
#include <memory>

#include "camera/filter.h"
#include "core/object.h"
#include "core/transform.h"
#include "core/vector.h"

namespace snell {

/// Film settings (Mitsuba's hdrfilm): size and optional crop window, in pixels, and the pixel
/// reconstruction filter.
struct FilmSpec {
    int width = 768, height = 576;
    int crop_x = 0, crop_y = 0, crop_w = 0, crop_h = 0;  ///< crop_w == 0: whole image
    /// Reconstruction filter (camera/filter.h); nullptr means the one-pixel box. Scene files
    /// without an <rfilter> get Mitsuba's default, a gaussian of stddev 0.5.
    std::shared_ptr<const Filter> filter;
    int out_width() const { return crop_w ? crop_w : width; }
    int out_height() const { return crop_h ? crop_h : height; }
    /// The filter to use: `filter`, or the box when there is none.
    const Filter& pixel_filter() const { return filter ? *filter : *box_filter(); }
    /// How far (pixels) beyond the output window the filters of its pixels reach: radius - 1/2
    /// (0 for the box). Techniques that place samples on the film themselves (light tracing,
    /// Metropolis) cover the window grown by this margin, as filtered camera samples do.
    Vec2 filter_margin() const {
        const Vec2 r = pixel_filter().radius();
        return {std::max(0.0, r.x - 0.5), std::max(0.0, r.y - 0.5)};
    }
    /// The output window grown by filter_margin(), in full-film raster coordinates.
    Vec2 sample_origin() const { return Vec2(crop_x - filter_margin().x, crop_y - filter_margin().y); }
    Vec2 sample_extent() const {
        return Vec2(out_width() + 2 * filter_margin().x, out_height() + 2 * filter_margin().y);
    }
};

/// A sensor: primary rays through the film. Cameras with a lens read a 2D lens sample; light
/// paths can be connected to pinhole cameras only (BDPT's t = 1 strategies, light tracing).
class Camera : public Object {
public:
    /// Primary ray through continuous full-film raster position (x right, y down, pixels);
    /// `u_lens` in [0, 1)^2 picks the point on the aperture (ignored without a lens).
    virtual Ray generate_ray(const Vec2& raster, const Vec2& u_lens) const = 0;
    /// generate_ray reads u_lens: callers draw one only then, so pinhole renders keep their
    /// sample streams.
    virtual bool has_lens() const { return false; }
    /// This camera as a pinhole light paths can connect to, or nullptr.
    virtual const class PerspectiveCamera* pinhole() const { return nullptr; }
    const FilmSpec& film() const { return m_film; }
    const Transform& to_world() const { return m_to_world; }

protected:
    Camera(const Transform& to_world, const FilmSpec& film) : m_to_world(to_world), m_film(film) {}

    Transform m_to_world;
    FilmSpec m_film;
};

/// Mitsuba's `perspective` sensor: pinhole camera looking down +z in camera space,
/// +x to the left, +y up; `fov` along `fov_axis` (x, y, smaller, larger, diagonal).
class PerspectiveCamera : public Camera {
public:
    PerspectiveCamera(const Transform& to_world, double fov_deg, const std::string& fov_axis, const FilmSpec& film,
                      double near_clip = 1e-2, double far_clip = 1e4);
    /// Primary ray through continuous full-film raster position (x right, y down, pixels).
    Ray generate_ray(const Vec2& raster) const;
    Ray generate_ray(const Vec2& raster, const Vec2& /*u_lens*/) const override { return generate_ray(raster); }
    const PerspectiveCamera* pinhole() const override { return this; }
    Vec3 position() const { return m_to_world.point(Vec3(0, 0, 0)); }
    /// Unit optical axis in world space.
    Vec3 forward() const { return normalize(m_to_world.vector(Vec3(0, 0, 1))); }
    /// Full-film raster position at which world point `p` is seen (the inverse of
    /// generate_ray); false when p lies behind the camera, outside the film grown by `margin`
    /// pixels on each side, or outside the clip range. `cos_theta` receives the cosine between
    /// the direction to p and the optical axis.
    bool raster_of(const Vec3& p, Vec2* raster, double* cos_theta, const Vec2& margin = Vec2(0, 0)) const;
    /// Area, on the image plane at unit distance, of one pixel.
    double pixel_plane_area() const { return 4.0 * m_tx * m_ty / (double(m_film.width) * double(m_film.height)); }
    /// Tangent of half the horizontal / vertical field of view.
    double tan_half_x() const { return m_tx; }
    double tan_half_y() const { return m_ty; }

protected:
    /// Camera-space direction (z = 1 plane) through a raster position.
    Vec3 image_plane_point(const Vec2& raster) const {
        return Vec3((1.0 - 2.0 * raster.x / m_film.width) * m_tx, (1.0 - 2.0 * raster.y / m_film.height) * m_ty, 1.0);
    }

    Transform m_to_camera;  // the inverse of to_world (light tracing projects points)
    double m_tx, m_ty, m_near, m_far;
};

}  // namespace snell
