// `make bench`: renderer throughput on the demo scene (the built-in droplet at 320x240) against
// Embree's raw closest-hit rate on the same geometry. Never part of `make test`.
//
// What each benchmark measures (all use every hardware thread through TBB):
//   BM_RenderPath / BM_RenderNEE   the whole renderer (`render()`, 4 spp per iteration): camera
//                                  rays, BSDF and light sampling, spectral accumulation.
//                                  paths/s = camera paths; rays/s = closest-hit + shadow queries;
//                                  closest/s = closest-hit queries only.
//   BM_EmbreeRawRandomRays         rtcIntersect1 alone on incoherent rays: origins uniform in the
//                                  scene's bounding box, directions uniform on the sphere. A
//                                  generic figure, but not the renderer's workload: half of
//                                  these rays start in empty space above the ground and leave
//                                  the scene at once.
//   BM_EmbreeRawRendererRays       rtcIntersect1 alone on the rays `path` itself traces: a
//                                  buffer recorded beforehand by following camera paths through
//                                  the scene with BSDF sampling (same pixel order, depth limit
//                                  and Russian roulette as the renderer). This is the fair
//                                  ceiling for the renderer's closest/s.
//   BM_SceneIntersectRendererRays  the same buffer through Scene::intersect, which adds the
//                                  double-precision ray set-up and the full differential
//                                  geometry every hit carries (dp/du, dn/du, ...): the cost of
//                                  the geometry layer on top of Embree.
// Both raw benchmarks pass the double-precision ray through the context exactly as
// Scene::intersect does, because the analytic sphere's intersection callback reads it there.
//
// The *Serial variants run the same work on the benchmark's own thread (render() with one
// thread; the ray buffers without TBB) and report rates per CPU second of that thread rather
// than per wall second: on a machine shared with other jobs, wall-clock rates move with the
// load, CPU-time rates much less. Compare renderer and Embree figures within one run.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "builtin_scenes.h"
#include "core/rng.h"
#include "core/spectrum.h"
#include "core/stats.h"
#include "core/warp.h"
#include "geometry/embree_context.h"
#include "integrators/integrator.h"
#include "loader/scene_loader.h"
#include "render/camera_sample.h"
#include "render/renderer.h"
#include "scene/scene.h"

using namespace snell;

namespace {

constexpr int kResX = 320, kResY = 240;

LoadedScene& demo_scene(const std::string& integrator) {
    static std::map<std::string, LoadedScene> cache;
    auto it = cache.find(integrator);
    if (it == cache.end()) {
        Defines d{{"integrator", integrator}, {"res_x", std::to_string(kResX)}, {"res_y", std::to_string(kResY)}};
        it = cache
                 .emplace(integrator, load_scene_string(*builtin_scene("droplet"), "builtin:droplet",
                                                        std::filesystem::current_path().string(), d))
                 .first;
    }
    return it->second;
}

// Full renderer: camera rays, BSDF and light sampling, spectral accumulation, all threads.
void render_bench(benchmark::State& state, const char* integrator, int threads = 0) {
    LoadedScene& ls = demo_scene(integrator);
    RenderOptions opt;
    opt.spp = 4;
    opt.sampler = ls.sampler;
    opt.progress = false;
    opt.threads = threads;
    StatTotals total;
    for (auto _ : state) {
        RenderResult r = render(*ls.scene, *ls.integrator, ls.film, opt);
        total += r.counters;
        benchmark::DoNotOptimize(r.film.xyz(0, 0));
    }
    const double paths = double(total[render_stats::paths]), rays = double(total[scene_stats::rays]);
    const double all_rays = rays + double(total[scene_stats::shadow_rays]);
    state.counters["paths/s"] = benchmark::Counter(paths, benchmark::Counter::kIsRate);
    state.counters["rays/s"] = benchmark::Counter(all_rays, benchmark::Counter::kIsRate);
    state.counters["closest/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
    state.counters["rays/path"] = all_rays / std::max(1.0, paths);
}
void BM_RenderPath(benchmark::State& s) { render_bench(s, "pt"); }
void BM_RenderNEE(benchmark::State& s) { render_bench(s, "nee"); }
void BM_RenderMNEE(benchmark::State& s) { render_bench(s, "mnee"); }
void BM_RenderBDPT(benchmark::State& s) { render_bench(s, "bdpt"); }
void BM_RenderPathSerial(benchmark::State& s) { render_bench(s, "pt", 1); }
void BM_RenderNEESerial(benchmark::State& s) { render_bench(s, "nee", 1); }

/// One closest-hit query straight to Embree (no differential geometry, no shading).
bool embree_closest_hit(RTCScene scene, const Ray& ray) {
    RayContext ctx(ray);  // the sphere callback reads the double ray from here
    RTCRayHit rh;
    rh.ray.org_x = float(ray.o.x), rh.ray.org_y = float(ray.o.y), rh.ray.org_z = float(ray.o.z);
    rh.ray.dir_x = float(ray.d.x), rh.ray.dir_y = float(ray.d.y), rh.ray.dir_z = float(ray.d.z);
    rh.ray.tnear = float(std::max(0.0, ray.tmin));
    rh.ray.tfar = float(ray.tmax);
    rh.ray.time = 0;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx.ctx, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

/// Traces every ray of `rays` with `trace` on all threads (or, `serial`, on this one);
/// reports rays/s and the hit fraction.
template <typename Trace>
void replay(benchmark::State& state, const std::vector<Ray>& rays, const Trace& trace, bool serial = false) {
    std::atomic<uint64_t> hits{0};
    uint64_t traced = 0;
    for (auto _ : state) {
        if (serial) {
            uint64_t local = 0;
            for (const Ray& r : rays) local += trace(r);
            hits += local;
        } else {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  uint64_t local = 0;
                                  for (size_t i = r.begin(); i < r.end(); ++i) local += trace(rays[i]);
                                  hits += local;
                              });
        }
        traced += rays.size();
    }
    state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] = double(hits.load()) / double(std::max<uint64_t>(1, traced));
}

/// Incoherent rays: origins uniform in the scene bounds, directions uniform on the sphere.
const std::vector<Ray>& random_rays() {
    static const std::vector<Ray> rays = [] {
        const Scene& scene = *demo_scene("nee").scene;
        const Bounds3 b = scene.bounds();
        PCG32 rng(1, 7);
        std::vector<Ray> out(size_t(1) << 20);
        for (Ray& r : out) {
            r.o = b.lo + Vec3(rng.next_double(), rng.next_double(), rng.next_double()) * b.extent();
            r.d = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
        }
        return out;
    }();
    return rays;
}

/// The closest-hit rays the `path` integrator traces on the demo scene, in the renderer's order
/// (16x16 tiles, pixel by pixel, path by path): camera rays through jittered pixel positions,
/// then BSDF-sampled continuations (refraction through the droplet included, four wavelengths per
/// path), with the scene's max_depth (12) and the renderer's Russian roulette from depth 5.
const std::vector<Ray>& renderer_rays() {
    static const std::vector<Ray> rays = [] {
        const LoadedScene& ls = demo_scene("pt");
        const Scene& scene = *ls.scene;
        const PerspectiveCamera& cam = *scene.camera()->pinhole();
        const int max_depth = 12, rr_depth = 5, spp = 4, tile = 16;
        PCG32 rng(2, 11);
        std::vector<Ray> out;
        out.reserve(size_t(kResX) * kResY * spp * 3);
        for (int ty = 0; ty < kResY; ty += tile)
            for (int tx = 0; tx < kResX; tx += tile)
                for (int y = ty; y < std::min(kResY, ty + tile); ++y)
                    for (int x = tx; x < std::min(kResX, tx + tile); ++x)
                        for (int s = 0; s < spp; ++s) {
                            const BSDFContext ctx{
                                SampledWavelengths::sample_visible({rng.next_double(), rng.next_double()}),
                                TransportMode::Radiance};
                            Ray ray = cam.generate_ray(Vec2(x + rng.next_double(), y + rng.next_double()));
                            SampledSpectrum beta(1.0);
                            double eta_scale = 1;
                            bool hero_only = false;
                            for (int depth = 0; depth < max_depth; ++depth) {
                                out.push_back(ray);
                                SurfaceInteraction si;
                                if (!scene.intersect(ray, &si) || !si.bsdf()) break;
                                const auto bs = si.bsdf()->sample(ctx, si.to_local(si.wo), rng.next_double(),
                                                                  {rng.next_double(), rng.next_double()});
                                if (!bs || bs->weight.is_zero()) break;
                                beta *= bs->weight;
                                if (bs->hero_only && !hero_only) beta = ctx.wl.hero_only(beta), hero_only = true;
                                if ((bs->lobe & kTransmission) && bs->eta != 1.0) eta_scale *= bs->eta * bs->eta;
                                ray = scene.spawn_ray(si, si.to_world(bs->wi));
                                if (depth + 1 >= rr_depth) {
                                    const double q = std::min(0.95, beta.max_component() * eta_scale);
                                    if (!(rng.next_double() < q)) break;
                                    beta /= q;
                                }
                            }
                        }
        return out;
    }();
    return rays;
}

void BM_EmbreeRawRandomRays(benchmark::State& state) {
    const RTCScene s = demo_scene("nee").scene->rtc_scene();
    replay(state, random_rays(), [s](const Ray& r) { return embree_closest_hit(s, r); });
}

void embree_raw_renderer_rays(benchmark::State& state, bool serial) {
    const RTCScene s = demo_scene("pt").scene->rtc_scene();
    const std::vector<Ray>& rays = renderer_rays();
    replay(
        state, rays, [s](const Ray& r) { return embree_closest_hit(s, r); }, serial);
    state.counters["rays/path"] = double(rays.size()) / double(kResX * kResY * 4);
}
void BM_EmbreeRawRendererRays(benchmark::State& state) { embree_raw_renderer_rays(state, false); }
void BM_EmbreeRawRendererRaysSerial(benchmark::State& state) { embree_raw_renderer_rays(state, true); }

void scene_intersect_renderer_rays(benchmark::State& state, bool serial) {
    const Scene& scene = *demo_scene("pt").scene;
    replay(
        state, renderer_rays(),
        [&scene](const Ray& r) {
            SurfaceInteraction si;
            return scene.intersect(r, &si);
        },
        serial);
}
void BM_SceneIntersectRendererRays(benchmark::State& state) { scene_intersect_renderer_rays(state, false); }
void BM_SceneIntersectRendererRaysSerial(benchmark::State& state) { scene_intersect_renderer_rays(state, true); }

}  // namespace

BENCHMARK(BM_EmbreeRawRandomRays)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_EmbreeRawRendererRays)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SceneIntersectRendererRays)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_RenderPath)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_RenderNEE)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_RenderMNEE)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_RenderBDPT)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_EmbreeRawRendererRaysSerial)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_SceneIntersectRendererRaysSerial)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_RenderPathSerial)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_RenderNEESerial)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK_MAIN();
