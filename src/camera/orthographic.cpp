#include "camera/orthographic.h"

namespace snell {

Ray OrthographicCamera::generate_ray(const Vec2& raster, const Vec2& /*u_lens*/) const {
    const double aspect = double(m_film.width) / double(m_film.height);
    const Vec3 p_cam(1.0 - 2.0 * raster.x / m_film.width, (1.0 - 2.0 * raster.y / m_film.height) / aspect, m_near);
    const Vec3 d = m_to_world.vector(Vec3(0, 0, 1));
    Ray r;
    r.o = m_to_world.point(p_cam);
    r.d = normalize(d);
    r.tmin = 0.0;
    r.tmax = (m_far - m_near) * length(d);
    return r;
}

}  // namespace snell
