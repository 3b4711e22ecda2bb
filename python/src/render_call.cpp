// Scene.render's native half: the render runs on a worker thread without the GIL while the
// calling thread waits in short naps. Between naps it takes the GIL for a moment to do what
// only a Python thread may: check for Ctrl-C (PyErr_CheckSignals, the main thread's signal
// handlers), read the stop handle, call the progress callback. Ctrl-C or a stop ends the render
// at the next work item (RenderStop), and the film so far comes back as a stopped render does
// from the command line.
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "app_common.h"
#include "bindings.h"
#include "core/props.h"
#include "integrators/integrator.h"
#include "render/team_pass.h"

namespace snell::py {

namespace {

using Clock = std::chrono::steady_clock;

// One render at a time in a process: the statistics registry (core/stats.h) is the process's.
std::mutex& render_mutex() {
    static std::mutex m;
    return m;
}

// How often the waiting thread looks up, and the least time between two progress calls.
constexpr auto kNap = std::chrono::milliseconds(20);
constexpr double kProgressInterval = 0.2;  // seconds

// Seconds left, from the fraction done and the time so far (-1: not known yet).
double eta_seconds(double fraction, double elapsed, double time_limit) {
    if (time_limit > 0) return std::max(0.0, time_limit - elapsed);
    if (fraction >= 1) return 0;
    return fraction > 0 ? elapsed * (1 - fraction) / fraction : -1;
}

struct RenderArgs {
    std::optional<int> spp;
    std::optional<uint64_t> seed;
    std::optional<double> time;
    std::optional<int> threads;
    bool strategies = false;
};

RenderOptions render_options(const PyScene& s, const RenderArgs& a) {
    if (a.spp && (*a.spp < 1 || *a.spp > (1 << 30)))
        throw pyb::value_error("spp must be in [1, 2^30], got " + std::to_string(*a.spp));
    if (a.time && !(std::isfinite(*a.time) && *a.time > 0))
        throw pyb::value_error("time must be a positive, finite number of seconds, got " + std::to_string(*a.time));
    if (a.threads && (*a.threads < 0 || *a.threads > 4096))
        throw pyb::value_error("threads must be in [0, 4096] (0: all cores), got " + std::to_string(*a.threads));
    if (a.spp && a.time) throw pyb::value_error("give spp or time, not both");
    RenderOptions opt;
    opt.spp = a.spp ? *a.spp : s.ls.spp;
    // As `snell render`: the scene's time budget (Mitsuba's `timeout`) unless spp or time is given.
    opt.time_limit = a.time ? *a.time : (a.spp ? 0 : s.ls.time_limit);
    opt.threads = a.threads.value_or(0);
    opt.seed = a.seed.value_or(s.ls.seed);
    opt.sampler = s.ls.sampler;
    opt.progress = false;
    opt.debug_layers = a.strategies;
    return opt;
}

// The film a Python image views: the linear sRGB buffers and the stats `snell render` writes.
std::unique_ptr<PyFilm> make_film(RenderResult&& r, const PyScene& s, const Integrator& integ,
                                  const RenderOptions& opt) {
    auto f = std::make_unique<PyFilm>();
    f->result = std::move(r);
    const Film& film = f->result.film;
    f->width = film.width();
    f->height = film.height();
    f->rgb = film.to_linear_srgb(0);
    for (size_t k = 0; k < f->result.layer_names.size(); ++k) f->layers.push_back(film.to_linear_srgb(int(k) + 1));
    RenderReport rep =
        make_report(s.name, integ.name(), s.ls.film.out_width(), s.ls.film.out_height(), f->result,
                    opt.time_limit > 0 ? 0 : uint64_t(opt.spp), opt.time_limit, render_threads(opt), opt.seed);
    rep.beyond_float = film.values_beyond_float();
    f->stats = rep;
    return f;
}

// Returns (film, exception or None): the exception is a KeyboardInterrupt that stopped the
// render, or what the progress callback raised; python/snell/_scene.py raises it with the image.
pyb::tuple render_scene(const PyScene& scene, const pyb::object& integrator, const RenderArgs& args,
                        const pyb::object& progress, const pyb::object& stop) {
    const std::shared_ptr<Integrator> integ = integrator_from(integrator, scene);
    RenderOptions opt = render_options(scene, args);
    const StopHandle* handle = stop.is_none() ? nullptr : &stop.cast<const StopHandle&>();
    const bool report_progress = !progress.is_none();
    if (report_progress && !PyCallable_Check(progress.ptr()))
        throw pyb::type_error("progress: expected a callable progress(fraction, eta_seconds) or None");
    std::atomic<double> fraction{0};
    if (report_progress) opt.progress_fraction = &fraction;

    // A progress callback that renders would wait for its own render (one at a time).
    static thread_local bool rendering = false;
    if (rendering) throw std::runtime_error("render: called from the progress callback of a render on this thread");
    struct Mark {
        Mark() { rendering = true; }
        ~Mark() { rendering = false; }
    } mark;

    std::atomic<bool> cancel{false};
    std::optional<RenderResult> result;
    std::exception_ptr failure;
    bool done = false;
    std::mutex m;
    std::condition_variable finished;
    pyb::object pending = pyb::none();
    {
        pyb::gil_scoped_release nogil;
        std::lock_guard<std::mutex> one_at_a_time(render_mutex());
        const auto start = Clock::now();
        auto last_call = start - std::chrono::hours(1);
        std::thread worker([&] {
            try {
                result.emplace(render(*scene.ls.scene, *integ, scene.ls.film, opt, &cancel));
            } catch (...) {
                failure = std::current_exception();
            }
            std::lock_guard<std::mutex> lock(m);
            done = true;
            finished.notify_all();
        });
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(m);
                if (finished.wait_for(lock, kNap, [&] { return done; })) break;
            }
            if (cancel.load()) continue;  // stopping: wait for the pass to end
            pyb::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {                 // Ctrl-C (or another signal whose handler raised)
                pending = pyb::error_already_set().value();  // takes the error off the thread state
                cancel = true;
            } else if (handle && handle->requested.load()) {
                cancel = true;
            } else if (report_progress) {
                const auto now = Clock::now();
                const double since = std::chrono::duration<double>(now - last_call).count();
                if (since >= kProgressInterval) {
                    last_call = now;
                    const double f = fraction.load(), t = std::chrono::duration<double>(now - start).count();
                    try {
                        const double eta = eta_seconds(f, t, opt.time_limit);
                        progress(f, eta < 0 ? pyb::object(pyb::none()) : pyb::float_(eta));
                    } catch (pyb::error_already_set& e) {
                        pending = e.value();
                        cancel = true;
                    }
                }
            }
        }
        worker.join();
    }
    if (failure) std::rethrow_exception(failure);
    if (report_progress && pending.is_none()) progress(fraction.load(), 0.0);  // the last call: where it ended
    pyb::object film = pyb::cast(make_film(std::move(*result), scene, *integ, opt));
    return pyb::make_tuple(film, pending);
}

}  // namespace

void bind_render(pyb::module_& m) {
    pyb::class_<StopHandle>(m, "StopHandle")
        .def(pyb::init<>())
        .def("stop", [](StopHandle& h) { h.requested = true; })
        .def_property_readonly("stopped", [](const StopHandle& h) { return h.requested.load(); });
    m.def(
        "render",
        [](const PyScene& scene, const pyb::object& integrator, std::optional<int> spp, std::optional<uint64_t> seed,
           std::optional<double> time, std::optional<int> threads, const pyb::object& progress, const pyb::object& stop,
           bool strategies) {
            return render_scene(scene, integrator, RenderArgs{spp, seed, time, threads, strategies}, progress, stop);
        },
        pyb::arg("scene"), pyb::arg("integrator"), pyb::arg("spp"), pyb::arg("seed"), pyb::arg("time"),
        pyb::arg("threads"), pyb::arg("progress"), pyb::arg("stop"), pyb::arg("strategies"));
}

}  // namespace snell::py
