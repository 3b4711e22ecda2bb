// libFuzzer target for the scene loader (issue 12): each input is a bundle (fuzz/bundle.h) of a
// scene and the files it reads. The bundle is written to a private temporary folder, loaded with
// load_scene_file and, when it loads, rendered tiny (at most 8 x 8 pixels, 1 spp, 1 thread, the
// render cancelled after SNELL_FUZZ_RENDER_SECONDS, default 2) with the scene's own integrator,
// so that crashes while building and rendering are found too. A SceneError or another
// std::exception with a message is a clean error; anything else (a crash, a sanitizer report,
// an exception without a message, a hang past -timeout) is a finding.
//
// At exit it prints "snell-fuzz: cases N, loaded L, rendered R, scene errors S, other errors O"
// and writes the same line to the file named by SNELL_FUZZ_STATS, if set. docs/testing.md
// says how to run it and how to reproduce a crash.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <string>
#include <thread>

#include "core/props.h"
#include "core/rgb_to_spectrum_table.h"
#include "fuzz/asset_mutator.h"
#include "fuzz/bundle.h"
#include "fuzz/xml_mutator.h"
#include "light/rgb_illuminant_table.h"
#include "loader/scene_loader.h"

namespace fs = std::filesystem;

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

namespace {

size_t copy_out(const std::string& out, uint8_t* data, size_t max_size) {
    if (out.size() > max_size) return 0;
    std::copy(out.begin(), out.end(), data);
    return out.size();
}

struct Counts {
    uint64_t cases = 0, loaded = 0, rendered = 0, scene_errors = 0, other_errors = 0;
};
Counts g_counts;
double g_render_seconds = 2;
bool g_verbose = false;  // SNELL_FUZZ_VERBOSE: one line per case (reproducing, checking the corpus)

void note(const char* outcome, const char* what) {
    if (g_verbose) std::fprintf(stderr, "snell-fuzz: %s%s%s\n", outcome, *what ? ": " : "", what);
}

void report_counts() {
    char line[256];
    std::snprintf(line, sizeof(line),
                  "snell-fuzz: cases %llu, loaded %llu, rendered %llu, scene errors %llu, other errors %llu\n",
                  (unsigned long long)g_counts.cases, (unsigned long long)g_counts.loaded,
                  (unsigned long long)g_counts.rendered, (unsigned long long)g_counts.scene_errors,
                  (unsigned long long)g_counts.other_errors);
    std::fputs(line, stderr);
    if (const char* path = std::getenv("SNELL_FUZZ_STATS")) std::ofstream(path) << line;
}

// A folder of its own under the system's temporary folder, removed with everything in it.
class TempDir {
public:
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "snell-fuzz-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) {
            std::perror("snell-fuzz: mkdtemp");
            std::abort();
        }
        m_path = tmpl;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(m_path, ec);
    }
    const fs::path& path() const { return m_path; }

private:
    fs::path m_path;
};

// Sets `cancel` once `seconds` have passed, unless destroyed first: bounds integrators whose
// settings ask for long renders (millions of mutations, huge depths).
class Watchdog {
public:
    Watchdog(std::atomic<bool>& cancel, double seconds)
        : m_thread([this, &cancel, seconds] {
              std::unique_lock lock(m_mutex);
              if (!m_cv.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return m_done; }))
                  cancel = true;
          }) {}
    ~Watchdog() {
        {
            std::lock_guard lock(m_mutex);
            m_done = true;
        }
        m_cv.notify_one();
        m_thread.join();
    }

private:
    std::mutex m_mutex;
    std::condition_variable m_cv;
    bool m_done = false;
    std::thread m_thread;
};

void render_tiny(snell::LoadedScene& ls) {
    if (!ls.integrator || !ls.scene) return;
    snell::FilmSpec film = ls.film;
    // The top-left corner of the film, so that the camera's own film (which maps rays) still fits.
    film.crop_x = film.crop_y = 0;
    film.crop_w = std::clamp(film.width, 1, 8);
    film.crop_h = std::clamp(film.height, 1, 8);
    snell::RenderOptions opt;
    opt.spp = 1;
    opt.threads = 1;
    opt.seed = ls.seed;
    opt.sampler = ls.sampler;
    opt.progress = false;
    std::atomic<bool> cancel = false;
    Watchdog dog(cancel, g_render_seconds);
    snell::render(*ls.scene, *ls.integrator, film, opt, &cancel);
}

void run_case(const uint8_t* data, size_t size) {
    const auto files = snell::fuzz::parse_bundle(std::string_view(reinterpret_cast<const char*>(data), size));
    TempDir dir;
    for (const auto& f : files) {
        const fs::path p = dir.path() / f.name;
        // Names may collide ("meshes" a file and "meshes/a.ply" in it): such a file is left out,
        // and the scene meets whatever is there, as a user's scene would.
        std::error_code ec;
        fs::create_directories(p.parent_path(), ec);
        if (ec) continue;
        std::ofstream(p, std::ios::binary).write(f.data.data(), std::streamsize(f.data.size()));
    }
    ++g_counts.cases;
    try {
        snell::LoadedScene ls = snell::load_scene_file((dir.path() / files.front().name).string());
        ++g_counts.loaded;
        render_tiny(ls);
        ++g_counts.rendered;
        note("rendered", "");
    } catch (const snell::SceneError& e) {
        ++g_counts.scene_errors;
        note("scene error", e.what());
    } catch (const std::exception& e) {
        // Every error a user can meet must say what went wrong.
        if (!e.what() || !*e.what()) {
            std::fprintf(stderr, "snell-fuzz: exception without a message\n");
            std::abort();
        }
        ++g_counts.other_errors;
        note("other error", e.what());
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (const char* s = std::getenv("SNELL_FUZZ_RENDER_SECONDS")) g_render_seconds = std::atof(s);
    g_verbose = std::getenv("SNELL_FUZZ_VERBOSE") != nullptr;
    // Tables built on first use (seconds under ASan) would make the first scene with a colour
    // look like a hang.
    snell::RGBToSpectrumTable::reflectance();
    snell::RGBIlluminantTable::get();
    std::atexit(report_counts);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    run_case(data, size);
    return 0;
}

// Mutates one file of the bundle: the XML files mostly through their tree (fuzz/xml_mutator.h),
// meshes and images half the time through their format (fuzz/asset_mutator.h), the rest as
// bytes. Now and then the whole bundle as bytes, which also renames, splits and merges files.
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size, unsigned int seed) {
    std::minstd_rand rng(seed);
    if (rng() % 20 == 0) return LLVMFuzzerMutate(data, size, max_size);
    auto files = snell::fuzz::parse_bundle(std::string_view(reinterpret_cast<const char*>(data), size));
    const bool bundled = size >= 7 && std::string_view(reinterpret_cast<const char*>(data), 7) == "@@file ";
    auto& f = files[rng() % files.size()];
    const bool xml = f.name.ends_with(".xml");
    const bool structured = xml ? rng() % 8 != 0 && snell::fuzz::mutate_scene_xml(f.data, rng())
                                : rng() % 2 == 0 && snell::fuzz::mutate_asset(f.name, f.data, rng());
    if (!structured) {
        const size_t budget = max_size > size ? max_size - size : 0;
        const size_t old = f.data.size();
        if (old + budget == 0) return LLVMFuzzerMutate(data, size, max_size);
        f.data.resize(old + budget);
        f.data.resize(LLVMFuzzerMutate(reinterpret_cast<uint8_t*>(f.data.data()), old, old + budget));
    }
    const std::string out = bundled ? snell::fuzz::write_bundle(files) : files.front().data;
    if (const size_t n = copy_out(out, data, max_size)) return n;
    return LLVMFuzzerMutate(data, size, max_size);
}

// Crossover by whole files, which keeps every file well formed (libFuzzer's byte crossover
// would cut XML mid-tag): the first bundle with one file of the second in place of the file
// of that name, or added to it.
extern "C" size_t LLVMFuzzerCustomCrossOver(const uint8_t* data1, size_t size1, const uint8_t* data2, size_t size2,
                                            uint8_t* out, size_t max_out_size, unsigned int seed) {
    std::minstd_rand rng(seed);
    auto files = snell::fuzz::parse_bundle(std::string_view(reinterpret_cast<const char*>(data1), size1));
    const auto other = snell::fuzz::parse_bundle(std::string_view(reinterpret_cast<const char*>(data2), size2));
    const auto& f = other[rng() % other.size()];
    auto same = std::find_if(files.begin(), files.end(), [&](const auto& g) { return g.name == f.name; });
    if (same != files.end())
        same->data = f.data;
    else if (files.size() < snell::fuzz::kMaxBundleFiles)
        files.push_back(f);
    return copy_out(snell::fuzz::write_bundle(files), out, max_out_size);
}
