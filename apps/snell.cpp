// The `snell` command: `snell render`, `snell merge`, `snell diff` and `snell compare`. This file
// only declares the command line; each sub-command lives in its own cmd_*.cpp.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "commands.h"
#include "render/mpi_team.h"

using namespace snell;

namespace {

// CLI11's PositiveNumber accepts "nan" and reports its range with a 300-digit bound (issue 12):
// these say what is expected.
const CLI::Validator kSeconds(
    [](std::string& in) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(in.c_str(), &end);
        if (end == in.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0))
            return "expected a positive, finite number of seconds, got '" + in + "'";
        return "";
    },
    "SECONDS>0");
// CLI11 reads "--seed -1" into a uint64_t as 2^64 - 1, and a seed of 2^64 or more as 2^64 - 1
// too; "--exposure nan" passed (issue 30). Both are refused here, saying what is expected.
const CLI::Validator kSeed(
    [](std::string& in) -> std::string {
        errno = 0;
        char* end = nullptr;
        const bool digits =
            !in.empty() && std::all_of(in.begin(), in.end(), [](unsigned char c) { return std::isdigit(c); });
        (void)std::strtoull(in.c_str(), &end, 10);
        if (!digits || errno == ERANGE) return "expected a seed in [0, 2^64 - 1] (decimal digits), got '" + in + "'";
        return "";
    },
    "SEED in [0, 2^64-1]");
const CLI::Validator kExposure(
    [](std::string& in) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(in.c_str(), &end);
        if (end == in.c_str() || *end != '\0' || !std::isfinite(v) || std::abs(v) > 64)
            return "expected an exposure in stops, a finite number in [-64, 64], got '" + in + "'";
        return "";
    },
    "STOPS in [-64, 64]");
const CLI::Validator kSpp = CLI::Range(int64_t(1), int64_t(1) << 30, "SPP in [1, 2^30]");
const CLI::Validator kThreads = CLI::Range(0, 4096, "THREADS in [0, 4096], 0 = all cores");

}  // namespace

// Under mpirun every rank runs main(); MPI ends with it, on every path out.
struct MpiSession {
    int status = 0;
    MpiSession(int& argc, char**& argv) : status(start_mpi_if_launched(argc, argv)) {}
    ~MpiSession() { finish_mpi(); }
};

int run(int argc, char** argv);

int main(int argc, char** argv) {
    MpiSession mpi(argc, argv);
    if (mpi.status) return mpi.status;
    return run(argc, argv);
}

int run(int argc, char** argv) {
    const bool lead = process_team().rank() == 0;
    CLI::App app{"snell: a spectral renderer for caustics through refractive interfaces (MNEE)"};
    app.require_subcommand(1);

    CLI::App* render_cmd = app.add_subcommand("render", "render a Mitsuba-style XML scene (or builtin:droplet)");
    RenderCommandOptions ro;
    uint64_t seed = 0;
    render_cmd->add_option("scene", ro.scene, "scene file, or builtin:droplet")->required();
    render_cmd->add_option("-o,--output", ro.out,
                           "output image: NAME.exr (with its PNG preview NAME.png) or NAME.png alone; a stats JSON "
                           "beside it; one %d or %0Nd is replaced by -D frame=N");
    auto* spp_opt =
        render_cmd->add_option("--spp", ro.spp, "samples per pixel (default: the scene's sample_count)")->check(kSpp);
    auto* time_opt =
        render_cmd->add_option("--time", ro.time_limit, "render for this many seconds instead (equal-time comparisons)")
            ->check(kSeconds)
            ->excludes(spp_opt);
    render_cmd->add_option("-t,--threads", ro.threads, "worker threads (default: all cores)")->check(kThreads);
    auto* seed_opt =
        render_cmd->add_option("--seed", seed, "sampler seed (default: the scene's <sampler> seed, else 0)")
            ->check(kSeed);
    render_cmd->add_option("--exposure", ro.exposure, "PNG exposure in stops")->check(kExposure);
    render_cmd->add_option("--stats", ro.stats_path, "stats JSON path (default: beside the image)");
    render_cmd->add_flag("--mkdir", ro.make_dirs, "create the folders of -o and --stats that do not exist");
    render_cmd->add_option("-D,--define", ro.defines, "override a scene <default>: -D name=value")
        ->allow_extra_args(false);
    render_cmd
        ->add_option("-a,--search-path", ro.search_paths,
                     "folder to find the scene's files in after its own (Mitsuba's -a; ';' separates several)")
        ->allow_extra_args(false);
    render_cmd->add_flag("-q,--quiet", ro.quiet, "no progress bar or summary");
    render_cmd->add_flag("--strategies", ro.strategies,
                         "bdpt: also write each strategy's weighted contribution, OUT_d<k>_s<s>_t<t>.exr");
    render_cmd
        ->add_option("--crop", ro.crop,
                     "x,y,w,h: render only these pixels, as a partial film for snell merge (a farm task)")
        ->excludes(time_opt);
    render_cmd
        ->add_option("--sample-range", ro.sample_range,
                     "a:b: render only the samples a ... b-1 of every pixel, as a partial film for snell merge")
        ->excludes(time_opt);
    render_cmd->add_option("--progress", ro.progress, "bar (on a terminal), lines (JSON lines on stdout) or none")
        ->check(CLI::IsMember({"bar", "lines", "none"}));

    CLI::App* merge_cmd =
        app.add_subcommand("merge", "add partial films (render --crop / --sample-range) into the frame");
    std::vector<std::string> merge_parts;
    std::string merge_out, merge_stats;
    double merge_exposure = 0;
    bool merge_quiet = false;
    merge_cmd->add_option("parts", merge_parts, "partial film EXRs")->required();
    merge_cmd
        ->add_option("-o,--output", merge_out,
                     "output image: NAME.exr (with its PNG preview) or NAME.png; a stats JSON beside it")
        ->required();
    merge_cmd->add_option("--exposure", merge_exposure, "PNG exposure in stops")->check(kExposure);
    merge_cmd->add_option("--stats", merge_stats, "stats JSON path (default: beside the image)");
    bool merge_mkdir = false;
    merge_cmd->add_flag("--mkdir", merge_mkdir, "create the folders of -o and --stats that do not exist");
    merge_cmd->add_flag("-q,--quiet", merge_quiet, "no summary");

    CLI::App* diff_cmd = app.add_subcommand("diff", "error metrics of an image against a reference (both EXR)");
    std::string diff_a, diff_b;
    std::vector<std::string> diff_crops;
    bool diff_json = false;
    diff_cmd->add_option("image", diff_a, "image to evaluate")->required();
    diff_cmd->add_option("reference", diff_b, "reference image")->required();
    diff_cmd->add_option("--crop", diff_crops, "also report the rectangle x,y,w,h (repeatable)");
    std::string diff_offset;
    diff_cmd->add_option(
        "--reference-offset", diff_offset,
        "x,y: the reference covers only the window of its size at (x, y) of the image (a crop render)");
    std::string diff_image_offset;
    diff_cmd
        ->add_option("--image-offset", diff_image_offset,
                     "x,y: the image is a crop render covering the window of its size at (x, y) of the reference; "
                     "the reference (and --normalise-by) are cut to it, --crop is in the reference's coordinates")
        ->excludes("--reference-offset");
    std::string diff_normalise;
    diff_cmd->add_option("--normalise-by", diff_normalise,
                         "EXR whose values r give relMSE's denominators (r^2 + 0.01) instead of the reference's, "
                         "e.g. a converged reference when comparing two noisy renders; the reference's size, or "
                         "with --reference-offset the window's (the reference is then cut to it too), or with "
                         "--image-offset the reference's (cut to the image) or the image's");
    diff_cmd->add_flag("--json", diff_json, "print JSON instead of text");

    CLI::App* cmp_cmd =
        app.add_subcommand("compare", "equal-time comparison of integrators against a reference, with an HTML report");
    CompareOptions cmp;
    uint64_t cmp_seed = 0;
    cmp_cmd->add_option("scene", cmp.scene, "scene file, or builtin:droplet")->required();
    cmp_cmd
        ->add_option("--integrators", cmp.integrators,
                     "comma-separated: pt, path, nee, bdpt, erpt, hslt, mnee, mnee-biased, mnee-paper, pssmlt(nee), "
                     "pssmlt(mnee)")
        ->required()
        ->delimiter(',');
    cmp_cmd->add_option("--time", cmp.time, "wall-clock seconds per integrator")->required()->check(kSeconds);
    cmp_cmd->add_option("-o,--out", cmp.out_dir, "report folder (created)")->required();
    auto* ref_file = cmp_cmd->add_option("--reference", cmp.reference_file, "reference EXR");
    auto* ref_integ = cmp_cmd->add_option("--reference-integrator", cmp.reference_integrator,
                                          "integrator that renders the reference (default mnee)");
    auto* ref_spp =
        cmp_cmd->add_option("--reference-spp", cmp.reference_spp, "reference samples per pixel")->check(kSpp);
    auto* ref_time =
        cmp_cmd->add_option("--reference-time", cmp.reference_time, "reference render time (s)")->check(kSeconds);
    cmp_cmd
        ->add_option("--reference-offset", cmp.reference_offset,
                     "x,y: the --reference file covers only the window of its size at (x, y) of the film (a long "
                     "render of the region that matters); every image and metric covers that window, the whole "
                     "film is kept as NAME_film.exr, --crop stays in film coordinates")
        ->needs(ref_file);
    ref_file->excludes(ref_integ)->excludes(ref_spp)->excludes(ref_time);
    ref_spp->excludes(ref_time);
    cmp_cmd->add_option("-D,--define", cmp.defines, "override a scene <default>: -D name=value")
        ->allow_extra_args(false);
    cmp_cmd->add_option("--crop", cmp.crops, "also evaluate and show the rectangle x,y,w,h (repeatable)");
    cmp_cmd->add_option("-t,--threads", cmp.threads, "worker threads, the same for every integrator (default: all)")
        ->check(kThreads);
    auto* cmp_seed_opt =
        cmp_cmd->add_option("--seed", cmp_seed, "sampler seed (default: the scene's, else 0)")->check(kSeed);
    cmp_cmd->add_option("--exposure", cmp.exposure, "PNG exposure in stops")->check(kExposure);
    cmp_cmd
        ->add_option("--convergence-steps", cmp.convergence_steps,
                     "extra renders at budget/2^k, k = N..1, for the convergence plot (0: none)")
        ->check(CLI::Range(0, 20));
    cmp_cmd->add_option("--error-max", cmp.error_max, "relative error at the top of the false-colour scale")
        ->check(CLI::PositiveNumber);
    cmp_cmd->add_flag("-q,--quiet", cmp.quiet, "no progress lines");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // Help and version exit 0; every usage error exits 2 with CLI11's message (rank 0's
        // alone under MPI: every rank parses the same line).
        if (!lead) {
            std::ostringstream sink;
            return app.exit(e, sink, sink) == 0 ? kExitOk : kExitUsage;
        }
        return app.exit(e) == 0 ? kExitOk : kExitUsage;
    }
    try {
        if (diff_cmd->parsed())
            return cmd_diff(diff_a, diff_b, diff_crops, diff_offset, diff_image_offset, diff_normalise, diff_json);
        if (render_cmd->parsed()) {
            if (seed_opt->count()) ro.seed = seed;
            return cmd_render(ro);
        }
        if (merge_cmd->parsed())
            return cmd_merge(merge_parts, merge_out, merge_exposure, merge_stats, merge_quiet, merge_mkdir);
        if (cmp_cmd->parsed()) {
            if (cmp_seed_opt->count()) cmp.seed = cmp_seed;
            if (cmp.reference_file.empty() && cmp.reference_spp == 0 && cmp.reference_time == 0)
                throw std::runtime_error(
                    "compare needs a reference: --reference ref.exr, or --reference-spp N / --reference-time S "
                    "(rendered with --reference-integrator, default mnee)");
            return cmd_compare(cmp);
        }
    } catch (const std::exception& e) {
        // Under MPI a rank that fails (a missing file on its node, say) ends the whole job.
        if (process_team().size() > 1) process_team().fail(e.what(), kExitError);
        std::fprintf(stderr, "snell: error: %s\n", e.what());
        return kExitError;
    }
    return kExitOk;
}
