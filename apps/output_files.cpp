#include "output_files.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace snell {

namespace {

std::string lower_extension(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

// Two names of one file: compared after resolving what exists (links, "..", ".").
bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ea, eb;
    const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea), cb = fs::weakly_canonical(fs::absolute(b), eb);
    if (ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
    return ca == cb;
}

void check_folder(const fs::path& file, const char* option, bool make_dirs) {
    const fs::path dir = file.parent_path();
    if (dir.empty()) return;
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return;
    if (fs::exists(dir, ec))
        throw std::runtime_error(std::string(option) + " " + file.string() + ": '" + dir.string() +
                                 "' is not a folder");
    if (!make_dirs)
        throw std::runtime_error(std::string(option) + " " + file.string() + ": the folder '" + dir.string() +
                                 "' does not exist (create it, or pass --mkdir)");
    fs::create_directories(dir, ec);
    if (ec)
        throw std::runtime_error(std::string(option) + " " + file.string() + ": cannot create '" + dir.string() +
                                 "': " + ec.message());
}

}  // namespace

fs::path OutputFiles::stem() const {
    const fs::path& p = exr.empty() ? png : exr;
    return p.parent_path() / p.stem();
}

OutputFiles output_files(const std::string& out, const std::string& stats, const std::string& fallback, bool make_dirs,
                         bool exr_only) {
    const fs::path name = out.empty() ? fs::path(fallback) : fs::path(out);
    std::error_code ec;
    if (fs::is_directory(name, ec))
        throw std::runtime_error("-o " + name.string() + " is a folder: give a file name, such as " +
                                 (name / "out.exr").string());
    const std::string ext = lower_extension(name);
    OutputFiles f;
    if (ext == ".exr") {
        f.exr = name;
        f.png = fs::path(name).replace_extension(".png");
    } else if (ext == ".png" && !exr_only) {
        f.png = name;
    } else {
        throw std::runtime_error("-o " + name.string() +
                                 (exr_only ? ": a partial film is an OpenEXR file; the name must end in .exr"
                                           : ": the name must end in .exr (the linear image, with its PNG preview "
                                             "beside it) or .png (an 8-bit sRGB image alone)"));
    }
    f.stats = stats.empty() ? fs::path(name).replace_extension(".json") : fs::path(stats);
    if (fs::is_directory(f.stats, ec)) throw std::runtime_error("--stats " + f.stats.string() + " is a folder");
    for (const fs::path& image : {f.exr, f.png})
        if (!image.empty() && same_file(image, f.stats))
            throw std::runtime_error("--stats " + f.stats.string() + " names the image " + image.string() +
                                     " that -o writes: the JSON would replace it");
    if (!f.exr.empty()) check_folder(f.exr, "-o", make_dirs);
    if (!f.png.empty()) check_folder(f.png, "-o", make_dirs);
    check_folder(f.stats, "--stats", make_dirs);
    return f;
}

}  // namespace snell
