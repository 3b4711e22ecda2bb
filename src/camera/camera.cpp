#include "camera/camera.h"

#include <cmath>
#include <stdexcept>

namespace snell {

PerspectiveCamera::PerspectiveCamera(const Transform& to_world, double fov_deg, const std::string& fov_axis,
                                     const FilmSpec& film, double near_clip, double far_clip)
    : Camera(to_world, film), m_to_camera(to_world.inverse()), m_near(near_clip), m_far(far_clip) {
    const double aspect = double(film.width) / double(film.height);
    const double t = std::tan(0.5 * fov_deg * kPi / 180.0);
    std::string axis = fov_axis;
    if (axis == "smaller") axis = aspect >= 1 ? "y" : "x";
    if (axis == "larger") axis = aspect >= 1 ? "x" : "y";
    if (axis == "x") {
        m_tx = t;
        m_ty = t / aspect;
    } else if (axis == "y") {
        m_ty = t;
        m_tx = t * aspect;
    } else if (axis == "diagonal") {
        const double d = std::sqrt(aspect * aspect + 1.0);
        m_tx = t * aspect / d;
        m_ty = t / d;
    } else {
        throw std::invalid_argument("unknown fov_axis '" + fov_axis + "' (x, y, smaller, larger, diagonal)");
    }
}

Ray PerspectiveCamera::generate_ray(const Vec2& raster) const {
    // Camera space: +z forward, +x left, +y up (Mitsuba); raster x grows to the right.
    const Vec3 d_cam = normalize(image_plane_point(raster));
    Ray r;
    r.o = m_to_world.point(Vec3(0, 0, 0));
    r.d = normalize(m_to_world.vector(d_cam));
    // Clip planes are distances along the optical axis.
    r.tmin = m_near / d_cam.z;
    r.tmax = m_far / d_cam.z;
    return r;
}

bool PerspectiveCamera::raster_of(const Vec3& p, Vec2* raster, double* cos_theta, const Vec2& margin) const {
    const Vec3 v = m_to_camera.point(p);
    const double len = length(v);
    if (!(v.z > 0) || !(len > 0)) return false;
    if (v.z < m_near || v.z > m_far) return false;  // clip planes are distances along the axis
    const double sx = v.x / (v.z * m_tx), sy = v.y / (v.z * m_ty);
    const Vec2 r((1.0 - sx) * 0.5 * m_film.width, (1.0 - sy) * 0.5 * m_film.height);
    if (!(r.x >= -margin.x && r.x < m_film.width + margin.x && r.y >= -margin.y && r.y < m_film.height + margin.y))
        return false;
    *raster = r;
    *cos_theta = v.z / len;
    return true;
}

}  // namespace snell
