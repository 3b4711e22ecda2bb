// `snell diff a.exr b.exr [--crop x,y,w,h]... [--reference-offset x,y] [--normalise-by r.exr]
// [--json]`: error metrics against a reference. A reference rendered on a crop of the film (a long
// render of the region that matters) is placed with --reference-offset; the image is cut to that
// window, and --crop rectangles stay in the image's own coordinates. The other way round, an image
// rendered on a crop (a quick look at the region that matters) is placed in a larger reference with
// --image-offset; the reference and the normaliser are cut to the image, and --crop rectangles are
// in the reference's coordinates. --normalise-by gives relMSE
// another denominator: two noisy renders compared with each other divide by a converged image,
// not by one of the noisy two (a firefly divided by itself would count as about 1).
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "app_common.h"
#include "commands.h"
#include "io/image.h"
#include "report/image_metrics.h"
#include "report/image_ops.h"

namespace snell {

int cmd_diff(const std::string& a_path, const std::string& b_path, const std::vector<std::string>& crops,
             const std::string& reference_offset, const std::string& image_offset, const std::string& normalise_by,
             bool json) {
    Image a = read_exr(a_path);
    Image b = read_exr(b_path);
    std::optional<Image> norm;
    if (!normalise_by.empty()) norm = read_exr(normalise_by);
    // The window: the normaliser's size where there is one, else the reference's.
    const Image& window = norm ? *norm : b;
    int ox = 0, oy = 0;
    if (!reference_offset.empty()) {
        const Crop o = offset_window("--reference-offset", reference_offset, window.width, window.height);
        for (Image* im : {&a, &b}) {
            if (im->width == window.width && im->height == window.height && im == &b) continue;
            if (!crop_inside(o, im->width, im->height))
                throw std::runtime_error("--reference-offset " + reference_offset + ": the window (" +
                                         std::to_string(window.width) + "x" + std::to_string(window.height) +
                                         ") does not fit inside the image (" + std::to_string(im->width) + "x" +
                                         std::to_string(im->height) + ")");
            *im = crop_image(*im, o);
        }
        ox = o.x;
        oy = o.y;
    }
    if (!image_offset.empty()) {
        const Crop o = offset_window("--image-offset", image_offset, a.width, a.height);
        // The normaliser is the reference's size (cut with it) or already the image's.
        if (norm && !(norm->width == a.width && norm->height == a.height) &&
            !(norm->width == b.width && norm->height == b.height))
            throw std::runtime_error("--normalise-by " + normalise_by + ": its size (" + std::to_string(norm->width) +
                                     "x" + std::to_string(norm->height) + ") is neither the reference's (" +
                                     std::to_string(b.width) + "x" + std::to_string(b.height) + ") nor the image's (" +
                                     std::to_string(a.width) + "x" + std::to_string(a.height) + ")");
        if (!crop_inside(o, b.width, b.height))
            throw std::runtime_error("--image-offset " + image_offset + ": the image (" + std::to_string(a.width) +
                                     "x" + std::to_string(a.height) + ") does not fit inside the reference (" +
                                     std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
        if (norm && norm->width == b.width && norm->height == b.height) *norm = crop_image(*norm, o);
        b = crop_image(b, o);
        ox = o.x;
        oy = o.y;
    }
    if (norm && (norm->width != b.width || norm->height != b.height))
        throw std::runtime_error("--normalise-by " + normalise_by + ": its size (" + std::to_string(norm->width) + "x" +
                                 std::to_string(norm->height) + ") is not the reference's (" + std::to_string(b.width) +
                                 "x" + std::to_string(b.height) + ")");
    std::vector<std::pair<std::string, Crop>> regions = {{"image", Crop{}}};
    for (const std::string& c : crops) {
        Crop r = parse_crop(c);
        if (!crop_inside({r.x - ox, r.y - oy, r.w, r.h}, b.width, b.height))
            throw std::runtime_error("--crop " + c + " lies outside the reference's window");
        r.x -= ox;
        r.y -= oy;
        regions.push_back({"crop " + c, r});
    }
    nlohmann::json out = nlohmann::json::array();
    for (const auto& [name, crop] : regions) {
        const ImageMetrics m = compare_images(a, b, crop, norm ? &*norm : nullptr);
        if (json) {
            nlohmann::json j = m;
            j["region"] = name;
            out.push_back(std::move(j));
        } else {
            std::printf(
                "%-24s relMSE %.6g  RMSE %.6g  PSNR %.3f dB  SMAPE %.6g  median error %.4g (RGB %.4g)  mean %.6g "
                "(reference %.6g)\n",
                name.c_str(), m.rel_mse, m.rmse, m.psnr, m.smape, m.median_rel_error, m.median_rel_error_rgb, m.mean,
                m.mean_reference);
        }
    }
    if (json) std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace snell
