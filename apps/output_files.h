#pragma once
// What `-o NAME` of `snell render` and `snell merge` writes (docs/rendering.md, "Output files").
// Issue 30: `-o DIR` wrote DIR.exr, `-o out.png` wrote out.png.exr, `-o /dev/full` wrote
// /dev/full.exr with exit 0, `--stats X.exr -o X.exr` replaced the image by the JSON, and missing
// folders were created unasked. Every name is settled before the render starts, so a mistake
// costs no render time.
#include <filesystem>
#include <string>

namespace snell {

struct OutputFiles {
    std::filesystem::path exr;    ///< the linear float image; empty for `-o NAME.png`
    std::filesystem::path png;    ///< the 8-bit sRGB image (beside the EXR, or alone)
    std::filesystem::path stats;  ///< the stats JSON
    /// The base of companion files (strategy images NAME_<layer>.exr): the name less its extension.
    std::filesystem::path stem() const;
};

/// The files of `-o out` (empty: `fallback`) and `--stats stats` (empty: NAME.json):
///   - NAME.exr writes the EXR and, by convention, its PNG preview NAME.png;
///   - NAME.png writes the PNG alone (refused when `exr_only`: a partial film is an EXR);
///   - any other name, a folder or a name without an extension is refused;
///   - the stats file may not be one of the images;
///   - a missing folder is an error unless `make_dirs` (--mkdir), which creates it.
/// Throws std::runtime_error saying what was given and what is expected.
OutputFiles output_files(const std::string& out, const std::string& stats, const std::string& fallback, bool make_dirs,
                         bool exr_only = false);

}  // namespace snell
