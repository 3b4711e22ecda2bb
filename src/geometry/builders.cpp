#include "geometry/builders.h"

#include <stdexcept>

namespace snell {

MeshData make_rectangle(const Transform& to_world) {
    MeshData m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise seen from +z
    transform_mesh(m, to_world);
    return m;
}

MeshData make_disk(const Transform& to_world, int segments) {
    if (segments < 3) throw std::runtime_error("disk: needs at least 3 segments");
    // Mitsuba's disk parametrisation: uv = (r, phi / 2 pi). A fan of triangles, each with its own
    // centre vertex (at phi of the triangle's middle) and the rim vertex at phi = 2 pi repeated
    // with v = 1, so that v never wraps inside a triangle.
    MeshData m;
    for (int i = 0; i <= segments; ++i) {
        const double phi = 2 * kPi * i / segments;
        m.positions.push_back({std::cos(phi), std::sin(phi), 0});
        m.uvs.push_back({1.0, double(i) / segments});
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t centre = uint32_t(m.positions.size());
        m.positions.push_back({0, 0, 0});
        m.uvs.push_back({0.0, (i + 0.5) / segments});
        m.triangles.push_back({centre, uint32_t(i), uint32_t(i + 1)});
    }
    transform_mesh(m, to_world);
    return m;
}

MeshData make_cube(const Transform& to_world) {
    MeshData m;
    // For each axis and sign: the face normal and two tangents with t1 x t2 = normal, so
    // corners listed counter-clockwise in (t1, t2) wind outward.
    for (int axis = 0; axis < 3; ++axis)
        for (int s = -1; s <= 1; s += 2) {
            Vec3 n, t1, t2;
            n[axis] = s;
            t1[(axis + 1) % 3] = 1;
            t2[(axis + 2) % 3] = 1;
            if (s < 0) std::swap(t1, t2);
            const uint32_t base = uint32_t(m.positions.size());
            const double c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (auto& cc : c) {
                m.positions.push_back(n + t1 * cc[0] + t2 * cc[1]);
                m.uvs.push_back({0.5 * (cc[0] + 1), 0.5 * (cc[1] + 1)});
            }
            m.triangles.push_back({base, base + 1, base + 2});
            m.triangles.push_back({base, base + 2, base + 3});
        }
    transform_mesh(m, to_world);
    return m;
}

}  // namespace snell
