#include "io/mesh_obj.h"

#include <tiny_obj_loader.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <tuple>

namespace snell {

MeshData load_obj(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": mesh file not found");

    tinyobj::ObjReaderConfig cfg;
    cfg.triangulate = true;
    cfg.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, cfg) || !reader.Valid())
        throw std::runtime_error(path + ": cannot parse OBJ: " + reader.Error());

    const tinyobj::attrib_t& a = reader.GetAttrib();
    const auto& shapes = reader.GetShapes();

    // Normals/uvs only if every corner has one; a partial set cannot be interpolated.
    bool has_n = !a.normals.empty(), has_uv = !a.texcoords.empty();
    for (const auto& s : shapes)
        for (const auto& idx : s.mesh.indices) {
            has_n = has_n && idx.normal_index >= 0;
            has_uv = has_uv && idx.texcoord_index >= 0;
        }

    MeshData m;
    std::map<std::tuple<int, int, int>, uint32_t> remap;
    const size_t np = a.vertices.size() / 3, nn = a.normals.size() / 3, nt = a.texcoords.size() / 2;
    auto vertex = [&](const tinyobj::index_t& idx) -> uint32_t {
        const int ni = has_n ? idx.normal_index : -1, ti = has_uv ? idx.texcoord_index : -1;
        const auto key = std::make_tuple(idx.vertex_index, ni, ti);
        auto it = remap.find(key);
        if (it != remap.end()) return it->second;
        if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= np || (has_n && size_t(ni) >= nn) ||
            (has_uv && size_t(ti) >= nt))
            throw std::runtime_error(path + ": face index out of range");
        const uint32_t id = uint32_t(m.positions.size());
        const size_t v = size_t(idx.vertex_index);
        m.positions.emplace_back(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]);
        if (has_n) m.normals.emplace_back(a.normals[3 * ni], a.normals[3 * ni + 1], a.normals[3 * ni + 2]);
        if (has_uv) m.uvs.emplace_back(a.texcoords[2 * ti], a.texcoords[2 * ti + 1]);
        remap.emplace(key, id);
        return id;
    };
    for (const auto& s : shapes) {
        size_t off = 0;
        for (size_t f = 0; f < s.mesh.num_face_vertices.size(); ++f) {
            const size_t nfv = s.mesh.num_face_vertices[f];
            // Triangulated by tinyobjloader; fan anything else defensively.
            for (size_t k = 1; k + 1 < nfv; ++k)
                m.triangles.push_back({vertex(s.mesh.indices[off]), vertex(s.mesh.indices[off + k]),
                                       vertex(s.mesh.indices[off + k + 1])});
            off += nfv;
        }
    }
    validate_mesh(m, path);
    return m;
}

}  // namespace snell
