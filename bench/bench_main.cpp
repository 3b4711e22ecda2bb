// `make bench`: renderer throughput on the demo scene against Embree's raw closest-hit rate on
// the same geometry (the ceiling a ray-bound renderer can reach). Never part of `make test`.
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <filesystem>
#include <memory>

#include "builtin_scenes.h"
#include "core/rng.h"
#include "core/stats.h"
#include "core/warp.h"
#include "geometry/scene.h"
#include "integrators/integrator.h"
#include "io/scene_loader.h"
#include "render/renderer.h"

using namespace snell;

namespace {

LoadedScene& demo_scene(const char* integrator) {
    static std::map<std::string, LoadedScene> cache;
    auto it = cache.find(integrator);
    if (it == cache.end()) {
        Defines d{{"integrator", integrator}, {"res_x", "320"}, {"res_y", "240"}};
        it = cache.emplace(integrator, load_scene_string(*builtin_scene("droplet"), "builtin:droplet",
                                                         std::filesystem::current_path().string(), d))
                 .first;
    }
    return it->second;
}

// Full renderer: camera rays, BSDF and light sampling, spectral accumulation, all threads.
void render_bench(benchmark::State& state, const char* integrator) {
    LoadedScene& ls = demo_scene(integrator);
    RenderOptions opt;
    opt.spp = 4;
    opt.progress = false;
    Counters total;
    for (auto _ : state) {
        RenderResult r = render(*ls.scene, *ls.scene->integrator(), ls.film, opt);
        total += r.counters;
        benchmark::DoNotOptimize(r.film.xyz(0, 0));
    }
    state.counters["paths/s"] = benchmark::Counter(double(total.paths), benchmark::Counter::kIsRate);
    state.counters["rays/s"] = benchmark::Counter(double(total.rays + total.shadow_rays), benchmark::Counter::kIsRate);
    state.counters["closest/s"] = benchmark::Counter(double(total.rays), benchmark::Counter::kIsRate);
}
void BM_RenderPath(benchmark::State& s) { render_bench(s, "path"); }
void BM_RenderNEE(benchmark::State& s) { render_bench(s, "nee"); }

// Embree alone: incoherent closest-hit queries (random origins in the scene bounds, random
// directions), with no shading at all, on all threads.
void BM_EmbreeRawClosestHit(benchmark::State& state) {
    LoadedScene& ls = demo_scene("nee");
    const Scene& scene = *ls.scene;
    const Bounds3 b = scene.bounds();
    const size_t n = 1 << 20;
    std::atomic<uint64_t> hits{0};
    uint64_t rays = 0;
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
            PCG32 rng(r.begin(), 7);
            RTCIntersectContext ctx;
            uint64_t local = 0;
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const Vec3 o = b.lo + Vec3(rng.next_double(), rng.next_double(), rng.next_double()) * b.extent();
                const Vec3 d = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
                rtcInitIntersectContext(&ctx);
                RTCRayHit rh{};
                rh.ray.org_x = float(o.x), rh.ray.org_y = float(o.y), rh.ray.org_z = float(o.z);
                rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
                rh.ray.tnear = 0.f;
                rh.ray.tfar = 1e30f;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene.rtc_scene(), &ctx, &rh);
                local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            hits += local;
        });
        rays += n;
    }
    state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] = double(hits.load()) / double(rays);
}

}  // namespace

BENCHMARK(BM_EmbreeRawClosestHit)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_RenderPath)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_RenderNEE)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK_MAIN();
