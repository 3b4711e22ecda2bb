#include "integrators/bdpt/bdpt.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/spectrum.h"
#include "integrators/bdpt/connect.h"
#include "integrators/bdpt/mis_weight.h"
#include "integrators/bdpt/subpath.h"
#include "integrators/bdpt/vertex.h"
#include "render/camera_sample.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace snell {

using namespace bdpt;

namespace {

/// BDPT for one render: the output window (camera importance) and whether debug layers are on.
class BdptTracer final : public SampleTracer {
public:
    BdptTracer(const PathSettings& settings, const FilmSpec& window, bool layers)
        : m_settings(settings), m_window(window), m_layers(layers) {}
    SampleEstimate li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                            SplatList& splats) const override;
    bool splats() const override { return true; }
    std::vector<std::string> layer_names() const override;

private:
    static constexpr int kMaxLayerDepth = 6;
    int max_layer_depth() const;
    /// Debug layer of strategy (s, t); -1 when it has none.
    int layer_of(int s, int t) const;

    PathSettings m_settings;
    FilmSpec m_window;
    bool m_layers;
};

int BdptTracer::max_layer_depth() const {
    return m_settings.max_depth > 0 ? std::min(m_settings.max_depth, kMaxLayerDepth) : kMaxLayerDepth;
}

int BdptTracer::layer_of(int s, int t) const {
    // Lengths k = 1, 2, ... in order; within one, s = 0 .. k (t = k + 1 - s >= 1), without (1, 1).
    int index = 1;
    for (int k = 1; k <= max_layer_depth(); ++k)
        for (int si = 0; si <= k; ++si) {
            if (si == 1 && k == 1) continue;
            if (si == s && k + 1 - si == t) return index;
            ++index;
        }
    return -1;
}

std::vector<std::string> BdptTracer::layer_names() const {
    std::vector<std::string> names;
    if (!m_layers) return names;
    for (int k = 1; k <= max_layer_depth(); ++k)
        for (int s = 0; s <= k; ++s) {
            const int t = k + 1 - s;
            if (s == 1 && t == 1) continue;
            // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a false positive) on
            // "literal" + std::to_string(...).
            std::string name = "d";
            name += std::to_string(k);
            name += "_s";
            name += std::to_string(s);
            name += "_t";
            name += std::to_string(t);
            names.push_back(std::move(name));
        }
    return names;
}

SampleEstimate BdptTracer::li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                                    SplatList& splats) const {
    ++render_stats::paths;
    const SampledWavelengths& wl = cs.wl;
    const int md = m_settings.max_depth;
    const PerspectiveCamera& camera = *scene.camera()->pinhole();  // the loader checked
    const Pinhole pinhole(camera, m_window);
    // Debug layers: each strategy's weighted contribution, at the pixel it reaches.
    // Camera strategies (t >= 2) belong to the sample's own pixel, as in the image; light
    // tracing (t = 1) lands wherever it projects, filtered like the image's splats.
    const auto record = [&](int s, int t, const SampledSpectrum& c, const Vec2& raster) {
        if (!m_layers) return;
        const int layer = layer_of(s, t);
        if (layer > 0 && c.is_nonzero()) splats.push_back({raster, wl.to_xyz(c), layer, t >= 2});
    };

    thread_local std::vector<Vertex> cam, lig;
    cam.clear();
    Vertex z0;
    z0.type = VertexType::Camera;
    z0.si.p = ray.o;
    z0.beta = SampledSpectrum(1.0);
    z0.pinhole = &pinhole;
    cam.push_back(z0);
    Escape esc;
    // max_depth counts segments: t <= max_depth + 1 (s = 0) and s <= max_depth (t = 1).
    const size_t cam_max = md < 0 ? size_t(kUnboundedVertices) : size_t(md) + 1;
    const size_t light_max = md < 0 ? size_t(kUnboundedVertices) : size_t(md);
    const double pdf_primary = pinhole.pdf_dir(dot(ray.d, camera.forward()));
    random_walk(scene, ray, sampler, wl, SampledSpectrum(1.0), pdf_primary, cam_max, m_settings.rr_depth,
                TransportMode::Radiance, cam, &esc);
    const SceneDisk disk(scene.bounds());
    light_subpath(scene, disk, sampler, wl, light_max, m_settings.rr_depth, lig);

    SampledSpectrum L;
    const int nc = int(cam.size()), nl = int(lig.size());
    // s = 0 is the one strategy for a path C S+ L (every vertex between delta): hidden with
    // hide_specular_emitters, which needs the camera vertices 1..t-2 all delta.
    int specular_prefix = 1;  // camera vertices 1..specular_prefix-1 are all delta
    while (specular_prefix < nc && cam[size_t(specular_prefix)].delta) ++specular_prefix;
    const auto hidden = [&](int t) {
        return t == 2 ? m_settings.hide_emitters : m_settings.hide_specular_emitters && t - 2 < specular_prefix;
    };
    for (int t = 2; t <= nc; ++t) {
        const Vertex& z = cam[size_t(t - 1)];
        // s = 0: the camera subpath ends on an area light.
        if (z.light && !hidden(t)) {
            const SampledSpectrum le = z.light->le(z.si.p, z.si.n, z.si.uv, z.si.wo, wl);
            if (le.is_nonzero()) {
                const SampledSpectrum c = z.beta * le * mis_weight(scene, disk, cam, lig, 0, t, wl);
                L += c;
                record(0, t, c, cs.pixel_centre);
            }
        }
        for (int s = 1; s <= nl; ++s) {
            if (md >= 0 && s + t - 1 > md) break;
            SampledSpectrum c = connect(scene, cam, lig, s, t, wl);
            if (c.is_nonzero()) {
                c *= mis_weight(scene, disk, cam, lig, s, t, wl);
                L += c;
                record(s, t, c, cs.pixel_centre);
            }
        }
    }
    // t = 1: light tracing. Each light vertex seen by the pinhole lands on its own pixel.
    for (int s = 2; s <= nl; ++s) {
        if (md >= 0 && s > md) break;
        Vec2 raster;
        SampledSpectrum c = connect_camera(scene, cam[0], lig[size_t(s - 1)], wl, &raster);
        if (c.is_zero()) continue;
        c *= mis_weight(scene, disk, cam, lig, s, 1, wl);
        if (c.is_nonzero()) splats.push_back({raster, wl.to_xyz(c), 0});
        record(s, 1, c, raster);
    }
    // s = 0 at infinity: the camera subpath escaped; its end is a vertex at infinity on each
    // light there, weighted against every strategy that could have built the same path.
    if (esc.escaped && !hidden(nc + 1)) {
        Vertex end;
        end.type = VertexType::Surface;
        end.infinite = true;
        end.dir = esc.d;
        end.beta = esc.beta;
        end.pdf_fwd = esc.pdf_dir;
        for (const Light* light : scene.infinite_lights()) {
            const SampledSpectrum le = light->le_escaped(esc.d, wl);
            if (le.is_zero()) continue;
            end.light = light;
            cam.push_back(end);
            const SampledSpectrum c = esc.beta * le * mis_weight(scene, disk, cam, lig, 0, nc + 1, wl);
            cam.pop_back();
            L += c;
            record(0, nc + 1, c, cs.pixel_centre);
        }
    }
    return L;
}

}  // namespace

std::unique_ptr<SampleTracer> BdptIntegrator::prepare(const Scene& scene, const FilmSpec& film,
                                                      const RenderOptions& options) const {
    if (!scene.camera() || !scene.camera()->pinhole())
        throw std::runtime_error(
            "bdpt connects light paths to the camera and needs a perspective (pinhole) sensor; render thinlens "
            "and orthographic sensors with path, pt, nee, mnee, direct, pssmlt or erpt");
    return std::make_unique<BdptTracer>(m_settings, film, options.debug_layers);
}

}  // namespace snell
