// `snell diff a.exr b.exr [--crop x,y,w,h]... [--json]`: error metrics against a reference.
#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "io/image.h"
#include "report/image_metrics.h"

namespace snell {

int cmd_diff(const std::string& a_path, const std::string& b_path, const std::vector<std::string>& crops, bool json) {
    const Image a = read_exr(a_path), b = read_exr(b_path);
    std::vector<std::pair<std::string, Crop>> regions = {{"image", Crop{}}};
    for (const std::string& c : crops) regions.push_back({"crop " + c, parse_crop(c)});
    nlohmann::json out = nlohmann::json::array();
    for (const auto& [name, crop] : regions) {
        const ImageMetrics m = compare_images(a, b, crop);
        if (json) {
            out.push_back({{"region", name},
                           {"rel_mse", m.rel_mse},
                           {"rmse", m.rmse},
                           {"psnr", m.psnr},
                           {"smape", m.smape},
                           {"mean", m.mean},
                           {"mean_reference", m.mean_reference},
                           {"median_rel_error", m.median_rel_error},
                           {"median_rel_error_rgb", m.median_rel_error_rgb}});
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
