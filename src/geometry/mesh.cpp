#include "geometry/mesh.h"

#include <algorithm>
#include <cfloat>
#include <cstring>
#include <stdexcept>

#include "core/warp.h"

namespace snell {

double TriangleMesh::position_error(const SurfaceInteraction& si) const {
    if (si.prim >= m_tris.size()) return shape_position_error();
    double m = 0;
    for (uint32_t i : m_tris[si.prim]) m = std::max(m, max_abs_component(m_pos[i].to_double()));
    return kFloatPositionError * m;
}

Vec2 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    // Walk the Voronoi regions of the vertices, then the edges, then the face interior.
    auto ratio = [](double num, double den) { return den != 0 ? num / den : 0.0; };
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {0, 0};  // vertex a
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {1, 0};  // vertex b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return {ratio(d1, d1 - d3), 0};  // edge ab
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 1};  // vertex c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return {0, ratio(d2, d2 - d6)};  // edge ac
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {  // edge bc
        const double w = ratio(d4 - d3, (d4 - d3) + (d5 - d6));
        return {1 - w, w};
    }
    const double inv = ratio(1.0, va + vb + vc);  // interior: barycentrics from sub-areas
    return {vb * inv, vc * inv};
}

TriangleMesh::TriangleMesh(MeshData data, bool face_normals, bool flip_normals, const std::string& name)
    : m_flip(flip_normals), m_name(name) {
    validate_mesh(data, name);
    m_pos.reserve(data.positions.size() + 1);
    for (const Vec3& p : data.positions) {
        m_pos.emplace_back(p);
        m_bounds.expand(m_pos.back().to_double());
    }
    for (const auto& p : m_pos)
        m_bounding_radius = std::max(m_bounding_radius, length(p.to_double() - m_bounds.center()));
    m_pos.emplace_back(0.f, 0.f, 0.f);  // padding read by Embree's vector loads
    m_tris = std::move(data.triangles);
    m_uvs = std::move(data.uvs);
    m_attributes = std::move(data.attributes);
    if (!face_normals && !data.normals.empty()) {
        m_normals = std::move(data.normals);
        for (Vec3& n : m_normals) {
            const double l = length(n);
            // A zero or broken normal cannot be interpolated; shade the mesh flat instead.
            if (!(l > 0) || !std::isfinite(l)) {
                m_normals.clear();
                break;
            }
            n /= l;
        }
    }
    std::vector<double> areas(m_tris.size());
    for (size_t i = 0; i < m_tris.size(); ++i) {
        const auto& t = m_tris[i];
        const Vec3 p0 = vertex(t[0]), p1 = vertex(t[1]), p2 = vertex(t[2]);
        areas[i] = 0.5 * length(cross(p1 - p0, p2 - p0));
        m_area += areas[i];
    }
    if (!(m_area > 0)) throw std::runtime_error(name + ": mesh has zero surface area");
    m_tri_dist = Distribution1D(std::move(areas));
    if (m_tris.size() <= kMaxCachedTriangles) {
        m_params.resize(m_tris.size());
        for (uint32_t i = 0; i < m_tris.size(); ++i) m_params[i] = triangle_params(i);
    }
}

const std::vector<std::array<uint32_t, 3>>& TriangleMesh::neighbours() const {
    std::call_once(m_neighbours_built, [this] { build_neighbours(); });
    return m_neighbours;
}

void TriangleMesh::build_neighbours() const {
    // Weld vertices by position (their float bits), so a seam of split normals or uvs joins.
    const size_t nv = vertex_count();
    std::vector<uint32_t> order(nv), weld(nv);
    for (uint32_t i = 0; i < nv; ++i) order[i] = i;
    const auto key = [&](uint32_t i) {
        std::array<uint32_t, 3> k;
        std::memcpy(k.data(), &m_pos[i], sizeof(k));
        return k;
    };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    for (size_t i = 0; i < nv; ++i)
        weld[order[i]] = i > 0 && key(order[i]) == key(order[i - 1]) ? weld[order[i - 1]] : order[i];
    // Every edge as (welded ends, triangle, edge index); edges met exactly twice join two triangles.
    struct Edge {
        uint64_t ends;
        uint32_t tri;
        uint32_t e;
    };
    std::vector<Edge> edges;
    edges.reserve(3 * m_tris.size());
    for (uint32_t t = 0; t < m_tris.size(); ++t)
        for (uint32_t e = 0; e < 3; ++e) {
            const uint32_t a = weld[m_tris[t][(e + 1) % 3]], b = weld[m_tris[t][(e + 2) % 3]];
            if (a == b) continue;  // a collapsed edge joins nothing
            edges.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), t, e});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.ends < y.ends; });
    m_neighbours.assign(m_tris.size(), {kNoNeighbour, kNoNeighbour, kNoNeighbour});
    for (size_t i = 0; i < edges.size();) {
        size_t j = i + 1;
        while (j < edges.size() && edges[j].ends == edges[i].ends) ++j;
        if (j - i == 2) {
            m_neighbours[edges[i].tri][edges[i].e] = edges[i + 1].tri;
            m_neighbours[edges[i + 1].tri][edges[i + 1].e] = edges[i].tri;
        }
        i = j;
    }
}

int TriangleMesh::attribute(const std::string& name, const SurfaceInteraction& si, double* out) const {
    for (const MeshAttribute& a : m_attributes) {
        if (a.name != name) continue;
        const size_t c = size_t(a.channels);
        if (si.prim >= m_tris.size()) return 0;
        if (a.per_face) {
            for (size_t k = 0; k < c; ++k) out[k] = a.values[size_t(si.prim) * c + k];
            return a.channels;
        }
        // Vertex attributes: barycentric interpolation at the point (si.uv may be the texture
        // map's, so the barycentrics are recovered from the position).
        const auto& t = m_tris[si.prim];
        const Vec2 b = closest_point_on_triangle(si.p, vertex(t[0]), vertex(t[1]), vertex(t[2]));
        const double w[3] = {1 - b.x - b.y, b.x, b.y};
        for (size_t k = 0; k < c; ++k) {
            out[k] = 0;
            for (int j = 0; j < 3; ++j) out[k] += w[j] * a.values[size_t(t[size_t(j)]) * c + k];
        }
        return a.channels;
    }
    return 0;
}

std::vector<std::string> TriangleMesh::attribute_names() const {
    std::vector<std::string> names;
    for (const MeshAttribute& a : m_attributes) names.push_back(a.name);
    return names;
}

TriangleMesh::~TriangleMesh() {
    if (m_query_scene) rtcReleaseScene(m_query_scene);
}

RTCGeometry TriangleMesh::make_geometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m_pos.data(), 0, sizeof(Vec3f),
                               vertex_count());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m_tris.data(), 0,
                               sizeof(std::array<uint32_t, 3>), m_tris.size());
    rtcCommitGeometry(g);
    return g;
}

unsigned TriangleMesh::attach(RTCDevice device, RTCScene scene) {
    RTCGeometry g = make_geometry(device);
    m_geom_id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    // Closest-point queries get their own BVH over this mesh only: Shape::closest_point has
    // no scene at hand, and a query in the shared BVH would also descend into every other
    // shape's nodes without ever shrinking its radius on them.
    if (!m_query_scene) {
        m_query_scene = rtcNewScene(device);
        rtcSetSceneFlags(m_query_scene, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry q = make_geometry(device);
        rtcAttachGeometry(m_query_scene, q);
        rtcReleaseGeometry(q);
        rtcCommitScene(m_query_scene);
    }
    return m_geom_id;
}

TriangleMesh::TriangleParams TriangleMesh::triangle_params(uint32_t prim) const {
    const auto& tri = m_tris[prim];
    const Vec3 p0 = vertex(tri[0]), p1 = vertex(tri[1]), p2 = vertex(tri[2]);
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    TriangleParams tp;
    const Vec3 ng = cross(e1, e2);
    const double ng_len = length(ng);
    tp.ng = ng_len > 0 ? ng / ng_len : Vec3(0, 0, 1);

    // Parametrisation: barycentric unless the texture map is usable.
    tp.dpdu = e1;
    tp.dpdv = e2;
    const bool smooth = !m_normals.empty();
    if (smooth) {
        const Vec3 n0 = m_normals[tri[0]];
        tp.dNdu = m_normals[tri[1]] - n0;
        tp.dNdv = m_normals[tri[2]] - n0;
    }
    if (!m_uvs.empty()) {
        const Vec2 t0 = m_uvs[tri[0]], t1 = m_uvs[tri[1]], t2 = m_uvs[tri[2]];
        const Vec2 d1 = t1 - t0, d2 = t2 - t0;
        const double det = d1.x * d2.y - d1.y * d2.x;
        // Relative test (sine of the angle between the uv edges): a collapsed uv triangle
        // cannot parametrise the surface, so keep the barycentric derivatives for it.
        if (std::abs(det) > 1e-9 * length(d1) * length(d2) && std::isfinite(1 / det)) {
            const double inv = 1 / det;
            // [e1 e2] = [dp/du dp/dv] [d1 d2]  =>  [dp/du dp/dv] = [e1 e2] [d1 d2]^-1
            tp.dpdu = (e1 * d2.y - e2 * d1.y) * inv;
            tp.dpdv = (e2 * d1.x - e1 * d2.x) * inv;
            if (smooth) {
                const Vec3 a = tp.dNdu, c = tp.dNdv;
                tp.dNdu = (a * d2.y - c * d1.y) * inv;
                tp.dNdv = (c * d1.x - a * d2.x) * inv;
            }
            tp.uv_map = true;
        }
    }
    // Flat shading: n is the (flipped) face normal, so the frame's s axis -- the Gram-Schmidt
    // step of Frame::from_normal_tangent -- is constant over the triangle.
    if (!smooth) {
        const Vec3 n = m_flip ? -tp.ng : tp.ng;
        Vec3 s = tp.dpdu - n * dot(n, tp.dpdu);
        const double l2 = length_squared(s);
        if (l2 > 1e-20) {
            s /= std::sqrt(l2);
            tp.flat_s = s;
            tp.flat_s_valid = true;
        }
    }
    return tp;
}

void TriangleMesh::interaction_at(uint32_t prim, const Vec2& b, SurfaceInteraction* si) const {
    if (m_params.empty())
        interaction_from(prim, b, triangle_params(prim), si);
    else
        interaction_from(prim, b, m_params[prim], si);
}

void TriangleMesh::interaction_from(uint32_t prim, const Vec2& b, const TriangleParams& tp,
                                    SurfaceInteraction* si) const {
    const auto& tri = m_tris[prim];
    const Vec3 p0 = vertex(tri[0]), p1 = vertex(tri[1]), p2 = vertex(tri[2]);
    const double b1 = b.x, b2 = b.y, b0 = 1 - b1 - b2;

    Vec2 uv = b;
    if (tp.uv_map) uv = m_uvs[tri[0]] * b0 + m_uvs[tri[1]] * b1 + m_uvs[tri[2]] * b2;

    Vec3 ng = tp.ng, n = tp.ng, dndu, dndv;
    const bool smooth = !m_normals.empty();
    if (smooth) {
        const Vec3 N = m_normals[tri[0]] * b0 + m_normals[tri[1]] * b1 + m_normals[tri[2]] * b2;
        const double len = length(N);
        if (len > 0) {
            n = N / len;
            // d(N/|N|) = (dN - n (n . dN)) / |N|
            dndu = (tp.dNdu - n * dot(n, tp.dNdu)) / len;
            dndv = (tp.dNdv - n * dot(n, tp.dNdv)) / len;
            ng = face_forward(ng, n);
        }
    }
    if (m_flip) {
        ng = -ng;
        n = -n;
        dndu = -dndu;
        dndv = -dndv;
    }
    si->p = p0 * b0 + p1 * b1 + p2 * b2;
    si->t = 0;
    si->ng = ng;
    si->n = n;
    si->dpdu = tp.dpdu;
    si->dpdv = tp.dpdv;
    si->dndu = dndu;
    si->dndv = dndv;
    si->uv = uv;
    si->shading = tp.flat_s_valid ? Frame(tp.flat_s, cross(n, tp.flat_s), n) : Frame::from_normal_tangent(n, tp.dpdu);
    si->shape = this;
    si->prim = prim;
}

void TriangleMesh::compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                                       SurfaceInteraction* si) const {
    // The point comes from the barycentrics rather than o + t d: it then lies on the triangle
    // up to double rounding, whatever the float error of Embree's t.
    interaction_at(prim, uv, si);
    si->t = t;
    si->wo = -normalize(ray.d);
}

namespace {

struct PointQueryData {
    const TriangleMesh* mesh = nullptr;
    Vec3 p;
    double best_d2 = kInfinity;
    double pad = 0;  ///< slack for the float query position Embree culls with
    uint32_t prim = 0;
    Vec2 b;
    bool found = false;
};

/// Float radius for Embree's culling that surely covers the double radius r around p.
float query_radius(double r, double pad) {
    const double padded = r + pad;
    if (!(padded < double(FLT_MAX))) return FLT_MAX;
    return std::nextafter(float(padded), FLT_MAX);
}

void visit_triangle(PointQueryData& q, uint32_t prim) {
    const auto& t = q.mesh->triangle(prim);
    const Vec3 a = q.mesh->vertex(t[0]), b = q.mesh->vertex(t[1]), c = q.mesh->vertex(t[2]);
    const Vec2 bc = closest_point_on_triangle(q.p, a, b, c);
    const Vec3 x = a + (b - a) * bc.x + (c - a) * bc.y;
    const double d2 = length_squared(x - q.p);
    if (d2 <= q.best_d2 && (!q.found || d2 < q.best_d2)) {
        q.best_d2 = d2;
        q.prim = prim;
        q.b = bc;
        q.found = true;
    }
}

bool point_query_callback(RTCPointQueryFunctionArguments* args) {
    auto& q = *static_cast<PointQueryData*>(args->userPtr);
    const bool had = q.found;
    const double before = q.best_d2;
    visit_triangle(q, args->primID);
    if (q.found && (!had || q.best_d2 < before)) {
        const float r = query_radius(std::sqrt(q.best_d2), q.pad);
        if (r < args->query->radius) {
            args->query->radius = r;
            return true;  // tells Embree the search sphere shrank
        }
    }
    return false;
}

}  // namespace

bool TriangleMesh::closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const {
    PointQueryData q;
    q.mesh = this;
    q.p = p;
    q.best_d2 = radius * radius;
    // Float rounding of the query point moves it by ~6e-8 |p| per axis; 1e-6 covers that.
    q.pad =
        1e-6 * (max_component(Vec3(std::abs(p.x), std::abs(p.y), std::abs(p.z))) + max_component(m_bounds.extent()));
    if (m_query_scene) {
        RTCPointQuery query;
        query.x = float(p.x);
        query.y = float(p.y);
        query.z = float(p.z);
        query.time = 0;
        query.radius = query_radius(radius, q.pad);
        RTCPointQueryContext ctx;
        rtcInitPointQueryContext(&ctx);
        rtcPointQuery(m_query_scene, &query, &ctx, point_query_callback, &q);
    } else {
        for (uint32_t i = 0; i < m_tris.size(); ++i) visit_triangle(q, i);
    }
    if (!q.found) return false;
    interaction_at(q.prim, q.b, si);
    si->wo = Vec3();
    return true;
}

bool TriangleMesh::closest_point_near(const SurfaceInteraction& near, const Vec3& p, double radius,
                                      SurfaceInteraction* si) const {
    // A point location walk from the vertex's triangle: while p lies beyond an edge, cross to
    // the neighbour past the one it lies furthest beyond. A walk's last steps stay on one
    // triangle and its first cross tens of a fine mesh's, far cheaper than the BVH's point
    // queries they replace (docs/experiments.md, "Cheaper walks on meshes"). The BVH answers
    // only at a boundary, a sliver, an edge point, or after kMaxProjectionHops crossings.
    if (near.shape == this && near.prim < m_tris.size()) {
        const std::vector<std::array<uint32_t, 3>>& across = neighbours();
        uint32_t prim = near.prim;
        for (int hop = 0; hop <= kMaxProjectionHops; ++hop) {
            // Everything this hop may read next is asked for at once, so that the misses of a
            // fine mesh overlap instead of following one another: this triangle's cached
            // parameters and vertex normals (for interaction_at) and its neighbours' indices
            // (for the next crossing).
            prefetch_params(prim);
            const auto& t = m_tris[prim];
            const auto& nb = across[prim];
            if (!m_normals.empty())
                for (uint32_t v : t) __builtin_prefetch(&m_normals[v]);
            for (uint32_t n : nb)
                if (n != kNoNeighbour) __builtin_prefetch(&m_tris[n]);
            const Vec3 a = vertex(t[0]), b = vertex(t[1]), c = vertex(t[2]);
            // Barycentrics of p's projection onto the triangle's plane.
            const Vec3 e1 = b - a, e2 = c - a, d = p - a;
            const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
            const double det = d11 * d22 - d12 * d12;
            if (!(det > 1e-12 * d11 * d22)) break;  // a sliver: let the BVH decide
            const double w1 = (d22 * dot(d, e1) - d12 * dot(d, e2)) / det;
            const double w2 = (d11 * dot(d, e2) - d12 * dot(d, e1)) / det;
            const double w[3] = {1 - w1 - w2, w1, w2};
            const int e = int(std::min_element(w, w + 3) - w);
            if (w[e] < 0) {
                // Beyond the edge opposite the most negative one: cross it.
                prim = nb[size_t(e)];
                if (prim == kNoNeighbour) break;
                continue;
            }
            const Vec2 bc = closest_point_on_triangle(p, a, b, c);
            if (!(bc.x > 0 && bc.y > 0 && bc.x + bc.y < 1)) break;  // on an edge: the BVH decides
            if (!(length_squared(a + e1 * bc.x + e2 * bc.y - p) <= radius * radius)) break;
            interaction_at(prim, bc, si);
            si->wo = Vec3();
            return true;
        }
    }
    return closest_point(p, radius, si);
}

ShapeSample TriangleMesh::sample_area(const Vec2& u) const {
    double pmf, ux;
    const uint32_t prim = uint32_t(m_tri_dist.sample_discrete(u.x, &pmf, &ux));
    const Vec2 w = warp::square_to_uniform_triangle({ux, u.y});  // weights of (p0, p1)
    SurfaceInteraction si;
    interaction_at(prim, {w.y, 1 - w.x - w.y}, &si);
    ShapeSample s;
    s.p = si.p;
    s.n = si.ng;
    s.uv = si.uv;
    s.p_error = position_error(si);
    s.pdf = 1.0 / m_area;
    return s;
}

}  // namespace snell
