#include "integrators/bdpt/mis_weight.h"

#include "scene/scene.h"

namespace snell::bdpt {

namespace {
// Densities that are 0 (delta lobes) cancel in the ratios: treat them as 1.
double remap0(double x) { return x != 0 ? x : 1.0; }
}  // namespace

double mis_weight(const Scene& scene, const SceneDisk& disk, const std::vector<Vertex>& cam,
                  const std::vector<Vertex>& lig, int s, int t, const SampledWavelengths& wl) {
    if (s + t == 2) return 1.0;  // (0, 2) only: light vertex to pinhole, (1, 1), is not taken
    thread_local std::vector<double> zr, zf, yr, yf;
    thread_local std::vector<char> zd, yd;
    zr.resize(size_t(t));
    zf.resize(size_t(t));
    zd.resize(size_t(t));
    yr.resize(size_t(s));
    yf.resize(size_t(s));
    yd.resize(size_t(s));
    for (int i = 0; i < t; ++i) zr[i] = cam[i].pdf_rev, zf[i] = cam[i].pdf_fwd, zd[i] = cam[i].delta;
    for (int i = 0; i < s; ++i) yr[i] = lig[i].pdf_rev, yf[i] = lig[i].pdf_fwd, yd[i] = lig[i].delta;
    const Vertex& z = cam[size_t(t - 1)];
    // The connection's endpoints scatter along the new edge, not along their sampled lobes.
    zd[t - 1] = false;
    bool light_delta = false;
    if (s == 0) {
        // z_{t-1} lies on an area light (or at infinity); seen as a light subpath it is y_0 and
        // emits to z_{t-2}.
        Vertex as_light = z;
        as_light.type = VertexType::Light;
        zr[t - 1] = light_origin_pdf(scene, z);
        zr[t - 2] = pdf_area(as_light, nullptr, cam[size_t(t - 2)], TransportMode::Importance, wl, disk);
    } else {
        const Vertex& y = lig[size_t(s - 1)];
        const Vertex* zp = t >= 2 ? &cam[size_t(t - 2)] : nullptr;
        yd[s - 1] = false;
        light_delta = delta_origin(*lig[0].light);
        if (t >= 2) {
            zr[t - 1] = pdf_area(y, s >= 2 ? &lig[size_t(s - 2)] : nullptr, z, TransportMode::Importance, wl, disk);
            zr[t - 2] = pdf_area(z, &y, *zp, TransportMode::Importance, wl, disk);
        }
        yr[s - 1] = pdf_area(z, zp, y, TransportMode::Radiance, wl, disk);  // t = 1: the pinhole's density
        if (s >= 2) yr[s - 2] = pdf_area(y, &z, lig[size_t(s - 2)], TransportMode::Radiance, wl, disk);
    }
    double sum = 0, r = 1;
    // Camera vertices handed to the light subpath: strategies (s + t - i, i), i >= 1 (the
    // pinhole z_0 cannot be hit, so t' = 0 does not exist).
    for (int i = t - 1; i >= 1; --i) {
        r *= remap0(zr[i]) / remap0(zf[i]);
        if (!zd[i] && !zd[i - 1]) sum += r * r;
    }
    r = 1;
    // Light vertices handed to the camera subpath: strategies (i, s + t - i), i < s.
    for (int i = s - 1; i >= 0; --i) {
        r *= remap0(yr[i]) / remap0(yf[i]);
        const bool prev_delta = i > 0 ? yd[i - 1] != 0 : light_delta;
        if (!yd[i] && !prev_delta) sum += r * r;
    }
    return 1.0 / (1.0 + sum);
}

}  // namespace snell::bdpt
