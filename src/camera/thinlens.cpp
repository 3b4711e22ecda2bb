#include "camera/thinlens.h"

#include "core/warp.h"

namespace snell {

Ray ThinLensCamera::generate_ray(const Vec2& raster, const Vec2& u_lens) const {
    // The pinhole ray's point on the focal plane stays where it is; the ray starts on the lens.
    const Vec3 through = image_plane_point(raster);  // z = 1
    const Vec3 focus = through * m_focus;
    const Vec2 lens = warp::square_to_uniform_disk_concentric(u_lens) * m_aperture;
    const Vec3 o_cam(lens.x, lens.y, 0.0);
    const Vec3 d_cam = normalize(focus - o_cam);
    Ray r;
    r.o = m_to_world.point(o_cam);
    const Vec3 d = m_to_world.vector(d_cam);
    r.d = normalize(d);
    // Clip planes are distances along the optical axis (camera space, as for the pinhole).
    const double per_t = length(d) / d_cam.z;  // world distance per unit of camera-space z
    r.tmin = m_near * per_t;
    r.tmax = m_far * per_t;
    return r;
}

}  // namespace snell
