#include "camera/camera.h"

#include "camera/field_of_view.h"

#include <cmath>
#include <stdexcept>

namespace snell {

PerspectiveCamera::PerspectiveCamera(const Transform& to_world, double fov_deg, const std::string& fov_axis,
                                     const FilmSpec& film, double near_clip, double far_clip)
    : Camera(to_world, film), m_to_camera(to_world.inverse()), m_near(near_clip), m_far(far_clip) {
    const Vec2 t = fov_tangents({fov_deg, fov_axis}, double(film.width) / double(film.height));
    m_tx = t.x;
    m_ty = t.y;
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
