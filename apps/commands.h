#pragma once
// The `snell` sub-commands; main() in snell.cpp parses the command line and calls one of these.
// Each returns the process exit status and throws std::exception with a user-facing message.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace snell {

/// Exit statuses of every sub-command (docs/rendering.md, "Exit codes").
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;          ///< a bad scene, a missing file, an I/O error, a failed rank
inline constexpr int kExitUsage = 2;          ///< a malformed command line
inline constexpr int kExitInterrupted = 130;  ///< Ctrl-C (or SIGTERM): the image so far was written

/// Options of `snell render` (docs/rendering.md).
struct RenderCommandOptions {
    std::string scene;
    std::string out;  ///< may hold one %d / %0Nd, replaced by the define `frame`
    int spp = 0;
    double time_limit = 0;
    int threads = 0;
    std::optional<uint64_t> seed;
    double exposure = 0;
    std::string stats_path;
    bool make_dirs = false;  ///< --mkdir: create missing folders of -o and --stats
    bool quiet = false;
    std::vector<std::string> defines;
    bool strategies = false;
    std::vector<std::string> search_paths;
    std::string crop;              ///< --crop x,y,w,h: a partial film of those pixels
    std::string sample_range;      ///< --sample-range a:b: a partial film of those samples
    std::string progress = "bar";  ///< --progress bar | lines | none
};

/// `snell render` (docs/rendering.md).
int cmd_render(const RenderCommandOptions& opt);

/// `snell merge part*.exr -o frame.exr`: partial films into the frame (docs/distributed.md).
int cmd_merge(const std::vector<std::string>& parts, std::string out, double exposure, std::string stats_path,
              bool quiet, bool make_dirs = false);

/// `out` with its one %d or %0Nd replaced by `frame` (-o frame_%04d.exr -D frame=12); `out`
/// unchanged without one. Throws std::runtime_error for other % patterns or a missing frame.
std::string output_name(const std::string& out, const std::optional<std::string>& frame);

/// `snell diff a.exr b.exr [--crop x,y,w,h]... [--reference-offset x,y | --image-offset x,y]
/// [--normalise-by r.exr] [--json]`: metrics of a against the reference b (apps/cmd_diff.cpp).
int cmd_diff(const std::string& a_path, const std::string& b_path, const std::vector<std::string>& crops,
             const std::string& reference_offset, const std::string& image_offset, const std::string& normalise_by,
             bool json);

/// Options of `snell compare` (docs/compare.md).
struct CompareOptions {
    std::string scene;
    std::vector<std::string> integrators;  ///< pt, path, nee, mnee, mnee-biased, ...
    double time = 0;                       ///< equal-time budget per integrator (s)
    std::string out_dir;
    std::string reference_file;    ///< --reference ref.exr
    std::string reference_offset;  ///< --reference-offset x,y: the reference covers that window of the film
    std::string reference_integrator = "mnee";
    int reference_spp = 0;      ///< --reference-spp
    double reference_time = 0;  ///< --reference-time
    std::vector<std::string> defines;
    std::vector<std::string> crops;  ///< "x,y,w,h"
    int threads = 0;
    std::optional<uint64_t> seed;
    double exposure = 0;
    int convergence_steps = 4;  ///< renders at budget/2^k, k = steps..1, before the full one
    double error_max = 1.0;     ///< top of the false-colour error scale
    bool quiet = false;
};

/// `snell compare`: equal-time renders, reference, metrics, report.html and report.json.
int cmd_compare(const CompareOptions& opt);

}  // namespace snell
