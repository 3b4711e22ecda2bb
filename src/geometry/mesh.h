#pragma once
#include <array>
#include <mutex>
#include <vector>

#include "core/distribution.h"
#include "core/mesh_data.h"
#include "geometry/shape.h"

namespace snell {

/// Triangle mesh. Positions are stored once in float (shared with Embree, so the surface
/// we shade is exactly the one Embree intersects); all derived quantities are double.
///
/// Orientation: ng = normalize((p1 - p0) x (p2 - p0)) (counter-clockwise winding is the
/// outside); with vertex normals ng is turned to the side of the interpolated normal; with
/// `flip_normals` both are negated afterwards.
///
/// Parametrisation for (u, v) and the derivatives: the texture coordinates when the mesh has
/// them and the triangle's uv map is not degenerate, otherwise the barycentrics (b1, b2) of
/// Embree's convention p = (1 - b1 - b2) p0 + b1 p1 + b2 p2. `si.uv` always reports the
/// coordinates the derivatives refer to.
///
/// Smooth shading: n = N/|N| with N the barycentric blend of vertex normals, and
/// dn/du = (dN/du - n (n . dN/du)) / |N| (derivative of the normalised normal). With
/// `face_normals` (or no vertex normals) n = ng and dn/du = dn/dv = 0.
class TriangleMesh final : public Shape {
public:
    /// Takes world-space data (see transform_mesh). Throws std::runtime_error("<name>: ...")
    /// on invalid data.
    TriangleMesh(MeshData data, bool face_normals = false, bool flip_normals = false, const std::string& name = "mesh");
    ~TriangleMesh() override;

    /// Attaches to `scene` and, once, builds a private Embree scene holding only this mesh
    /// for closest-point queries.
    unsigned attach(RTCDevice device, RTCScene scene) override;
    Bounds3 bounds() const override { return m_bounds; }
    /// Centred on the box, through the farthest vertex.
    BoundingSphere bounding_sphere() const override { return {m_bounds.center(), m_bounding_radius}; }
    double area() const override { return m_area; }
    /// From the hit triangle's vertices (pbrt-v4 bounds a triangle point by its barycentric
    /// sum of |p_i|; the largest vertex magnitude bounds that sum).
    double position_error(const SurfaceInteraction& si) const override;
    void compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                             SurfaceInteraction* si) const override;
    /// Exact closest point (double-precision point-triangle distance) within `radius`, found
    /// with an Embree point query on this mesh's private scene; before attach() it falls back
    /// to visiting every triangle.
    bool closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const override;
    /// Where p projects into the interior of the triangle `near` lies on, or of a triangle
    /// reached from it by crossing up to kMaxProjectionHops edges towards p, that projection
    /// (the closest point of the mesh wherever the mesh is convex towards p); elsewhere
    /// closest_point().
    bool closest_point_near(const SurfaceInteraction& near, const Vec3& p, double radius,
                            SurfaceInteraction* si) const override;
    /// Triangle chosen proportionally to area, then uniform on it; pdf = 1/area. The normal is
    /// the geometric normal (on the shading side).
    ShapeSample sample_area(const Vec2& u) const override;

    /// Fills `si` at barycentrics b = (b1, b2) (Embree convention) of triangle `prim`
    /// (t = 0, wo unset).
    void interaction_at(uint32_t prim, const Vec2& b, SurfaceInteraction* si) const;

    size_t triangle_count() const { return m_tris.size(); }
    size_t vertex_count() const { return m_pos.size() - 1; }  // minus Embree's padding
    Vec3 vertex(uint32_t i) const { return m_pos[i].to_double(); }
    const std::array<uint32_t, 3>& triangle(uint32_t i) const { return m_tris[i]; }
    bool has_vertex_normals() const { return !m_normals.empty(); }
    bool has_uvs() const { return !m_uvs.empty(); }
    int attribute(const std::string& name, const SurfaceInteraction& si, double* out) const override;
    std::vector<std::string> attribute_names() const override;

    /// Meshes with at most this many triangles keep the per-triangle part of the
    /// differential geometry (TriangleParams, 160 bytes a triangle: 160 MB at the limit)
    /// precomputed; larger ones recompute it at every hit rather than double their memory.
    /// A manifold walk builds an interaction at every projection, so a fine mesh's walks pay
    /// for recomputing it (the pool's, at the old limit of 2^16: docs/experiments.md, "The
    /// pool's blocks").
    static constexpr size_t kMaxCachedTriangles = size_t(1) << 20;
    /// Edges closest_point_near crosses before it asks the BVH. A walk's first steps move a
    /// vertex by up to half its distance to its neighbours (its trust region), tens of
    /// triangles of a fine mesh; its last ones stay on one. 64 leaves few of the pool's
    /// projections to the BVH (docs/experiments.md, "Cheaper walks on meshes").
    static constexpr int kMaxProjectionHops = 64;
    /// The triangle across edge e of triangle `prim` (the edge opposite its vertex e), or
    /// kNoNeighbour at a boundary or an edge shared by more than two triangles. Vertices at the
    /// same position count as one, so a mesh split at a seam of its normals or uvs is still
    /// connected across it. Built on first use (only the meshes a walk projects onto pay
    /// for them: 12 bytes a triangle, and 48 while building).
    uint32_t neighbour(uint32_t prim, int e) const { return neighbours()[prim][size_t(e)]; }
    static constexpr uint32_t kNoNeighbour = ~uint32_t(0);

private:
    /// Everything interaction_at needs that depends on the triangle alone, not on the
    /// barycentrics: computed by triangle_params() the same way whether cached or not, so
    /// both paths give bit-identical results.
    struct TriangleParams {
        Vec3 ng;              ///< unit winding normal, before face_forward and flipping
        Vec3 dpdu, dpdv;      ///< position derivatives in the chosen parametrisation
        Vec3 dNdu, dNdv;      ///< derivatives of the unnormalised blended normal (smooth only)
        bool uv_map = false;  ///< the texture map parametrises this triangle
        /// Flat shading (no vertex normals): the frame's s axis, which is then constant.
        Vec3 flat_s;
        bool flat_s_valid = false;
    };
    TriangleParams triangle_params(uint32_t prim) const;
    /// interaction_at given the triangle's parameters, read in place from the cache (no copy).
    void interaction_from(uint32_t prim, const Vec2& b, const TriangleParams& tp, SurfaceInteraction* si) const;
    /// Asks for triangle prim's cached parameters before interaction_at reads them: on a fine
    /// mesh that read misses the cache, and was a projection's longest wait (docs/experiments.md,
    /// twenty-second measurement). The point location walk visits the triangle it answers with.
    void prefetch_params(uint32_t prim) const {
        if (m_params.empty()) return;
        const char* p = reinterpret_cast<const char*>(&m_params[prim]);
        for (size_t off = 0; off < sizeof(TriangleParams); off += 64) __builtin_prefetch(p + off);
        __builtin_prefetch(p + sizeof(TriangleParams) - 1);
    }
    const std::vector<std::array<uint32_t, 3>>& neighbours() const;
    void build_neighbours() const;
    RTCGeometry make_geometry(RTCDevice device) const;

    std::vector<Vec3f> m_pos;  ///< one extra padding element: Embree reads 16 bytes per vertex
    std::vector<std::array<uint32_t, 3>> m_tris;
    std::vector<Vec3> m_normals;
    std::vector<Vec2> m_uvs;
    std::vector<MeshAttribute> m_attributes;
    bool m_flip;
    std::string m_name;
    Bounds3 m_bounds;
    double m_bounding_radius = 0;
    double m_area = 0;
    Distribution1D m_tri_dist;
    std::vector<TriangleParams> m_params;  ///< per triangle, empty above kMaxCachedTriangles
    mutable std::once_flag m_neighbours_built;
    mutable std::vector<std::array<uint32_t, 3>> m_neighbours;  ///< per triangle, across each edge
    RTCScene m_query_scene = nullptr;
};

/// Closest point on triangle (a, b, c) to p, in double (Voronoi-region walk, Ericson,
/// "Real-Time Collision Detection" 5.1.5). Returns the barycentrics (b1, b2) of the point,
/// which is a + b1 (b - a) + b2 (c - a).
Vec2 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace snell
