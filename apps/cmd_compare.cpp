// `snell compare SCENE --integrators a,b,... --time S --out DIR [reference] ...`: every integrator
// renders the same scene for the same wall-clock time on the same threads; each result is measured
// against a reference and the folder receives images, report.json and report.html (docs/compare.md).
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include "app_common.h"
#include "commands.h"
#include "core/props.h"
#include "integrators/integrator.h"
#include "loader/mitsuba_integrators.h"
#include "manifold/walk_statistics.h"
#include "render/render_team.h"
#include "render/renderer.h"
#include "render/team_pass.h"
#include "report/compare_report.h"
#include "report/false_colour.h"
#include "report/html_report.h"
#include "report/image_metrics.h"
#include "report/image_ops.h"
#include "scene/scene.h"

namespace fs = std::filesystem;

namespace snell {

namespace {

// A technique named on the command line: the integrator type plus its variant switches.
struct Technique {
    std::string name, type;
    bool biased = false;
    std::string sampler;  ///< inner sampler of Metropolis techniques ("nee", "mnee")
    /// `solutions` of an mnee variant ("one": the paper's estimator, Alg. 1 with Alg. 2's MIS),
    /// replacing the scene's; empty: the scene's or the default.
    std::string solutions;
};

Technique parse_technique(const std::string& name) {
    if (name == "pt" || name == "path" || name == "nee" || name == "mnee" || name == "bdpt" || name == "erpt" ||
        name == "hslt")
        return {name, name, false, "", ""};
    if (name == "mnee-biased" || name == "mnee(biased)") return {name, "mnee", true, "", ""};
    if (name == "mnee-paper" || name == "mnee(paper)") return {name, "mnee", false, "", "one"};
    if (name == "pssmlt(nee)") return {name, "pssmlt", false, "nee", ""};
    if (name == "pssmlt(mnee)") return {name, "pssmlt", false, "mnee", ""};
    throw std::runtime_error(
        "unknown integrator '" + name +
        "' (known: pt, path, nee, bdpt, erpt, hslt, mnee, mnee-biased or mnee(biased), mnee-paper or "
        "mnee(paper), pssmlt(nee), pssmlt(mnee))");
}

// A loaded scene and the integrator to render it with.
struct Prepared {
    LoadedScene ls;
    std::shared_ptr<Integrator> integrator;
};

// Loads the scene for one technique. Scenes that template their integrator
// (<integrator type="$integrator">) are loaded with -D integrator=TYPE, exactly as `snell render`
// would; for other scenes the integrator is built from the scene's <integrator> parameters with
// the type replaced, leaving out (with a note) those the type does not take. Either way the
// parameters written in the scene (max_depth, ...) apply.
Prepared prepare(const std::string& scene, const Defines& user_defines, const Technique& t, bool quiet) {
    Defines defines = user_defines;
    defines["integrator"] = t.type;
    std::shared_ptr<XmlObject> root;
    bool templated = true;
    try {
        root = parse_scene_arg(scene, defines);
    } catch (const std::exception&) {
        // Most likely the scene declares no `integrator` default; if it fails without the
        // define too, that error is the one to report.
        defines = user_defines;
        root = parse_scene_arg(scene, defines);
        templated = false;
    }
    Prepared p{load_scene_arg(scene, defines), nullptr};

    const XmlObject* xi = nullptr;
    for (const XmlObject::Child& c : root->children)
        if (c.obj->tag == "integrator") xi = c.obj.get();
    // Mitsuba's moment and aov wrappers: the parameters are the nested integrator's.
    if (xi) xi = &unwrap_integrator(*xi, nullptr);
    const SourceLoc loc = xi ? xi->loc : SourceLoc{scene, 0};
    std::set<std::string> dropped;  // scene parameters the technique's type does not take
    auto make = [&] {
        Props props("integrator", t.type, loc);
        if (xi)
            for (const XmlParam& prm : xi->params)
                if (!dropped.count(prm.name) && !(t.biased && prm.name == "biased") &&
                    !(!t.sampler.empty() && prm.name == "sampler") &&
                    !(!t.solutions.empty() && prm.name == "solutions"))
                    props.set(prm.name, prm.value, prm.loc);
        if (t.biased) props.set("biased", true, loc);
        if (!t.solutions.empty()) props.set("solutions", t.solutions, loc);
        if (!t.sampler.empty()) props.set("sampler", t.sampler, loc);
        return create_integrator(props);
    };
    for (;;) {
        try {
            p.integrator = make();
            break;
        } catch (const SceneError& e) {
            // The scene's own <integrator> (of another type) has a parameter this type does not
            // know, e.g. mnee's max_iterations for path: leave that one out and say so.
            if (templated || !xi) throw;
            const std::string msg = e.what();
            std::string culprit;
            for (const XmlParam& prm : xi->params)
                if (!dropped.count(prm.name) && msg.find("'" + prm.name + "'") != std::string::npos) culprit = prm.name;
            if (culprit.empty()) throw;
            dropped.insert(culprit);
            if (!quiet)
                std::fprintf(stderr, "snell: note: %s: ignoring the scene's <integrator> parameter '%s' (%s)\n",
                             t.name.c_str(), culprit.c_str(), msg.c_str());
        }
    }
    return p;
}

RenderResult run(const Prepared& p, double time_limit, int spp, int threads, uint64_t seed) {
    RenderOptions o;
    o.time_limit = time_limit;
    o.spp = spp > 0 ? spp : p.ls.spp;
    o.threads = threads;
    o.seed = seed;
    o.sampler = p.ls.sampler;
    o.progress = false;
    return render(*p.ls.scene, *p.integrator, p.ls.film, o, &g_cancel);
}

std::string fmt_seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g s", s);
    return buf;
}

std::string crop_text(const Crop& c) {
    return std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.w) + "," + std::to_string(c.h);
}

// Writes the enlarged crops of `img` as PREFIX_cropN.png; returns the file names.
std::vector<std::string> write_crops(const fs::path& dir, const std::string& prefix, const Image& img,
                                     const CompareReport& rep) {
    std::vector<std::string> names;
    for (size_t i = 0; i < rep.crops.size(); ++i) {
        const std::string name = prefix + "_crop" + std::to_string(i + 1) + ".png";
        write_png((dir / name).string(), upscale_nearest(crop_image(img, rep.crops[i]), rep.crop_scales[i]),
                  rep.exposure);
        names.push_back(name);
    }
    return names;
}

}  // namespace

int cmd_compare(const CompareOptions& options) {
    // Under mpirun (SNELL_LAUNCH="mpirun -n 4", docs/distributed.md) every rank renders each image
    // with the others and rank 0 alone reports: the other ranks stay quiet and write their
    // copies to a scratch folder that is removed at the end.
    const RenderTeam& team = process_team();
    const bool lead = team.rank() == 0;
    CompareOptions opt = options;
    if (!lead) {
        opt.quiet = true;
        opt.out_dir =
            (fs::temp_directory_path() / ("snell-compare-rank" + std::to_string(team.rank()) + "-" +
                                          std::to_string(uint64_t(std::hash<std::string>()(options.out_dir)))))
                .string();
    }
    struct Scratch {
        std::string dir;
        ~Scratch() {
            std::error_code ec;
            if (!dir.empty()) fs::remove_all(dir, ec);
        }
    } scratch{lead ? "" : opt.out_dir};
    // Validate everything cheap before the first render.
    if (opt.integrators.empty()) throw std::runtime_error("--integrators: name at least one integrator");
    std::vector<Technique> techniques;
    std::set<std::string> seen;
    for (const std::string& n : opt.integrators) {
        techniques.push_back(parse_technique(n));
        if (!seen.insert(n).second) throw std::runtime_error("--integrators: '" + n + "' given twice");
    }
    const Defines defines = parse_defines(opt.defines);
    if (defines.count("integrator"))
        throw std::runtime_error("-D integrator=... conflicts with --integrators (compare sets the integrator itself)");
    CompareReport rep;
    rep.scene = opt.scene;
    rep.defines = opt.defines;
    rep.time_budget = opt.time;
    rep.exposure = opt.exposure;
    rep.error_max = opt.error_max;
    for (const std::string& c : opt.crops) {
        try {
            rep.crops.push_back(parse_crop(c));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(std::string("--crop: ") + e.what());
        }
    }
    rep.threads = opt.threads > 0 ? opt.threads : render_threads(RenderOptions{});
    if (!opt.reference_offset.empty() && opt.reference_file.empty())
        throw std::runtime_error("--reference-offset places a --reference file: give one");
    // The offset's form is checked before any scene loads; its window needs the reference's size.
    if (!opt.reference_offset.empty()) offset_window("--reference-offset", opt.reference_offset, 1, 1);

    std::vector<Prepared> prepared;
    for (const Technique& t : techniques) prepared.push_back(prepare(opt.scene, defines, t, opt.quiet));
    const int film_w = prepared[0].ls.film.out_width(), film_h = prepared[0].ls.film.out_height();
    const uint64_t seed = opt.seed ? *opt.seed : prepared[0].ls.seed;
    rep.seed = seed;
    rep.film_width = film_w;
    rep.film_height = film_h;

    // A reference file is read first: its size is the film's, or with --reference-offset the
    // scored window's.
    Image ref;
    if (!opt.reference_file.empty()) ref = read_exr(opt.reference_file);
    std::optional<Crop> window;
    if (!opt.reference_offset.empty()) {
        window = offset_window("--reference-offset", opt.reference_offset, ref.width, ref.height);
        if (!crop_inside(*window, film_w, film_h))
            throw std::runtime_error("--reference-offset " + opt.reference_offset + ": the reference (" +
                                     std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                                     ") does not fit inside the " + std::to_string(film_w) + "x" +
                                     std::to_string(film_h) + " film");
    } else if (!opt.reference_file.empty() && (ref.width != film_w || ref.height != film_h)) {
        throw std::runtime_error("reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                                 " but the scene renders " + std::to_string(film_w) + "x" + std::to_string(film_h) +
                                 " (check -D res_x/res_y or the reference file, or place a crop reference with "
                                 "--reference-offset)");
    }
    const Crop scored = window ? *window : Crop{0, 0, film_w, film_h};
    rep.width = scored.w;
    rep.height = scored.h;
    rep.window_x = scored.x;
    rep.window_y = scored.y;
    for (Crop& c : rep.crops) {
        if (!crop_inside({c.x - scored.x, c.y - scored.y, c.w, c.h}, scored.w, scored.h))
            throw std::runtime_error("--crop " + crop_text(c) + " is outside the " + std::to_string(scored.w) + "x" +
                                     std::to_string(scored.h) +
                                     (window ? " reference window at " + std::to_string(scored.x) + "," +
                                                   std::to_string(scored.y) + " of the film"
                                             : " image"));
        c.x -= scored.x;  // the report works in the scored window's coordinates
        c.y -= scored.y;
        rep.crop_scales.push_back(enlargement_factor(c.w, c.h));
    }
    // A render as the report sees it: the scored window of the film.
    const auto scored_image = [&](const Film& film) {
        const Image full = film_to_image(film);
        return window ? crop_image(full, *window) : full;
    };

    const fs::path dir(opt.out_dir);
    fs::create_directories(dir);
    std::signal(SIGINT, on_sigint);

    // The reference: loaded, or rendered with its own seed so that its noise is independent of
    // the images it judges.
    ReferenceInfo& ri = rep.reference;
    if (!opt.reference_file.empty()) {
        ri.source = "file";
        ri.file = opt.reference_file;
    } else {
        ri.source = "render";
        ri.integrator = opt.reference_integrator;
        ri.spp = opt.reference_time > 0 ? 0 : uint64_t(opt.reference_spp);
        ri.time_limit = opt.reference_time;
        const Prepared p = prepare(opt.scene, defines, parse_technique(opt.reference_integrator), true);
        const uint64_t ref_seed = seed ^ 0x5eed5eed5eed5eedull;
        if (!opt.quiet)
            std::fprintf(
                stderr, "snell compare: reference %s, %s\n", ri.integrator.c_str(),
                ri.spp ? (std::to_string(ri.spp) + " spp").c_str() : (std::to_string(ri.time_limit) + " s").c_str());
        const RenderResult r = run(p, ri.time_limit, int(ri.spp), rep.threads, ref_seed);
        ri.stats = make_report(opt.scene, ri.integrator, p.ls.film.out_width(), p.ls.film.out_height(), r, ri.spp,
                               ri.time_limit, rep.threads, ref_seed);
        if (r.spp_completed == 0 && !g_cancel.load())
            throw std::runtime_error("the reference (" + ri.integrator + ", " + fmt_seconds(r.seconds) +
                                     ") drew no sample in some pixels: give it more --reference-time");
        ref = film_to_image(r.film);
    }
    ri.image_exr = "reference.exr";
    ri.image_png = "reference.png";
    write_exr((dir / ri.image_exr).string(), ref);
    write_png((dir / ri.image_png).string(), ref, rep.exposure);
    ri.crop_pngs = write_crops(dir, "reference", ref, rep);

    for (size_t i = 0; i < techniques.size() && !g_cancel.load(); ++i) {
        const Technique& t = techniques[i];
        const Prepared& p = prepared[i];
        IntegratorResult res;
        res.name = t.name;
        res.type = t.type;
        res.biased = t.biased;
        // Convergence: shorter renders at budget/2^k. Every render restarts from sample 0 with the
        // same seed, so each curve follows one progressive sample sequence.
        for (int k = opt.convergence_steps; k >= 1 && !g_cancel.load(); --k) {
            const double tl = opt.time / std::exp2(k);
            const RenderResult r = run(p, tl, 0, rep.threads, seed);
            res.convergence.push_back({tl, r.seconds, r.spp_mean, compare_images(scored_image(r.film), ref)});
        }
        if (!opt.quiet) std::fprintf(stderr, "snell compare: %s, %g s\n", t.name.c_str(), opt.time);
        const RenderResult r = run(p, opt.time, 0, rep.threads, seed);
        const Image img = scored_image(r.film);
        // With a reference window the whole film is kept beside the report's window.
        if (window) write_exr((dir / (t.name + "_film.exr")).string(), film_to_image(r.film));
        res.stats = make_report(opt.scene, t.name, p.ls.film.out_width(), p.ls.film.out_height(), r, 0, opt.time,
                                rep.threads, seed);
        res.regions.push_back({"image", Crop{}, compare_images(img, ref)});
        for (const Crop& c : rep.crops)
            res.regions.push_back({"crop " + crop_text(rep.in_film(c)), c, compare_images(img, ref, c)});
        res.convergence.push_back({opt.time, r.seconds, r.spp_mean, res.regions[0].metrics});
        if (r.interrupted)
            res.unranked = "interrupted after " + fmt_seconds(r.seconds);
        else if (r.spp_mean <= 0)
            res.unranked = "drew no sample in " + fmt_seconds(opt.time);
        else if (r.spp_completed == 0)
            res.unranked = "some pixels drew no sample in " + fmt_seconds(opt.time);

        res.image_exr = t.name + ".exr";
        res.image_png = t.name + ".png";
        res.error_png = t.name + "_error.png";
        write_exr((dir / res.image_exr).string(), img);
        write_png((dir / res.image_png).string(), img, rep.exposure);
        write_relative_error_png((dir / res.error_png).string(), img, ref, rep.error_max);
        res.crop_pngs = write_crops(dir, t.name, img, rep);
        if (!opt.quiet) {
            const ImageMetrics& m = res.regions[0].metrics;
            std::fprintf(stderr, "  %llu spp, %.3g paths/s, relMSE %.4g, PSNR %.2f dB\n",
                         (unsigned long long)r.spp_completed, res.stats.paths_per_second(), m.rel_mse, m.psnr);
        }
        rep.integrators.push_back(std::move(res));
    }
    std::signal(SIGINT, SIG_DFL);

    const fs::path json_path = dir / "report.json", html_path = dir / "report.html";
    {
        std::ofstream out(json_path);
        if (!(out << report_json(rep).dump(2) << "\n"))
            throw std::runtime_error("cannot write '" + json_path.string() + "'");
    }
    write_html_report(html_path.string(), rep);

    if (!lead) return g_cancel.load() ? 130 : 0;
    // Summary, best first.
    std::printf("%-4s %-12s %12s %10s %10s %10s %8s %12s\n", "rank", "integrator", "relMSE", "RMSE", "PSNR", "SMAPE",
                "spp", "paths/s");
    const std::vector<size_t> order = rep.order_by_psnr();
    for (size_t k = 0; k < order.size(); ++k) {
        const IntegratorResult& it = rep.integrators[order[k]];
        const ImageMetrics& m = it.regions[0].metrics;
        const std::string place = it.ranked() ? std::to_string(k + 1) : "-";
        std::printf("%-4s %-12s %12.5g %10.5g %10.3f %10.5g %8llu %12.4g%s\n", place.c_str(), it.name.c_str(),
                    m.rel_mse, m.rmse, m.psnr, m.smape, (unsigned long long)it.stats.spp_reached,
                    it.stats.paths_per_second(), it.ranked() ? "" : ("  not ranked: " + it.unranked).c_str());
    }
    std::printf("wrote %s and %s\n", html_path.c_str(), json_path.c_str());
    if (g_cancel.load()) {
        std::fprintf(stderr, "snell compare: interrupted; the report ranks the %zu of %zu integrators that finished\n",
                     rep.ranked_count(), techniques.size());
        return 130;
    }
    return 0;
}

}  // namespace snell
