#include "core/mesh_data.h"

#include <stdexcept>

namespace snell {

void transform_mesh(MeshData& mesh, const Transform& xf) {
    for (Vec3& p : mesh.positions) p = xf.point(p);
    for (Vec3& n : mesh.normals) {
        const Vec3 m = xf.normal(n);
        const double l = length(m);
        n = l > 0 ? m / l : m;
    }
    // A mirroring transform turns counter-clockwise into clockwise; swap two corners so the
    // winding (and with it the geometric normal) keeps meaning "outside".
    if (xf.det3() < 0)
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

void validate_mesh(const MeshData& mesh, const std::string& what) {
    auto fail = [&](const std::string& msg) { throw std::runtime_error(what + ": " + msg); };
    const size_t nv = mesh.positions.size();
    if (nv == 0) fail("mesh has no vertices");
    if (mesh.triangles.empty()) fail("mesh has no faces");
    if (!mesh.normals.empty() && mesh.normals.size() != nv) fail("normal count differs from vertex count");
    if (!mesh.uvs.empty() && mesh.uvs.size() != nv) fail("uv count differs from vertex count");
    for (const Vec3& p : mesh.positions)
        if (!is_finite(p)) fail("non-finite vertex position");
    for (const MeshAttribute& a : mesh.attributes) {
        const size_t n = a.per_face ? mesh.triangles.size() : nv;
        if ((a.channels != 1 && a.channels != 3) || a.values.size() != n * size_t(a.channels))
            fail("attribute '" + a.name + "' has " + std::to_string(a.values.size()) + " values for " +
                 std::to_string(n) + (a.per_face ? " faces" : " vertices"));
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
        for (uint32_t k : mesh.triangles[i])
            if (k >= nv)
                fail("face " + std::to_string(i) + " references vertex " + std::to_string(k) + " of " +
                     std::to_string(nv));
}

}  // namespace snell
