// snell.read, snell.write and snell.diff: the command line's image files and `snell diff`'s
// metrics, for numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "bindings.h"
#include "io/image.h"
#include "report/image_metrics.h"

namespace snell::py {

namespace {

using FloatArray = pyb::array_t<float, pyb::array::c_style | pyb::array::forcecast>;

Image to_image(const FloatArray& a, const char* what) {
    if (a.ndim() != 3 || a.shape(2) != 3)
        throw pyb::value_error(
            std::string(what) + ": expected an H x W x 3 array, got shape " +
            std::string(pyb::str(pyb::tuple(pyb::cast(std::vector<pyb::ssize_t>(a.shape(), a.shape() + a.ndim()))))));
    Image img;
    img.height = int(a.shape(0));
    img.width = int(a.shape(1));
    img.rgb.assign(a.data(), a.data() + a.size());
    return img;
}

pyb::array_t<float> to_array(Image&& img) {
    auto* owned = new std::vector<float>(std::move(img.rgb));
    pyb::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    const pyb::ssize_t w = img.width, h = img.height, fs = pyb::ssize_t(sizeof(float));
    return pyb::array_t<float>({h, w, pyb::ssize_t(3)}, {w * 3 * fs, 3 * fs, fs}, owned->data(), free_when_done);
}

std::string extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = char(std::tolower((unsigned char)c));
    return e;
}

}  // namespace

void bind_images(pyb::module_& m) {
    m.def(
        "read",
        [](const std::string& path) {
            Image img;
            {
                pyb::gil_scoped_release nogil;
                img = read_image(path);
            }
            return to_array(std::move(img));
        },
        pyb::arg("path"));
    m.def(
        "write",
        [](const std::string& path, const FloatArray& a, double exposure) {
            const Image img = to_image(a, "write");
            const std::string e = extension(path);
            if (e != ".exr" && e != ".png")
                throw pyb::value_error("write " + path +
                                       ": the name must end in .exr (linear float) or .png (8-bit sRGB)");
            pyb::gil_scoped_release nogil;
            if (e == ".exr")
                write_exr(path, img);
            else
                write_png(path, img, exposure);
        },
        pyb::arg("path"), pyb::arg("image"), pyb::arg("exposure"));
    m.def(
        "diff",
        [](const FloatArray& a, const FloatArray& b, std::optional<std::vector<int>> crop,
           std::optional<FloatArray> normalise_by) {
            const Image img = to_image(a, "diff: image"), ref = to_image(b, "diff: reference");
            std::optional<Image> norm;
            if (normalise_by) norm = to_image(*normalise_by, "diff: normalise_by");
            Crop c;
            if (crop) {
                if (crop->size() != 4) throw pyb::value_error("diff: crop must be (x, y, w, h)");
                c = {(*crop)[0], (*crop)[1], (*crop)[2], (*crop)[3]};
                if (c.w <= 0 || c.h <= 0) throw pyb::value_error("diff: crop width and height must be positive");
            }
            nlohmann::json j = compare_images(img, ref, c, norm ? &*norm : nullptr);
            j["region"] = crop ? "crop " + std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.w) +
                                     "," + std::to_string(c.h)
                               : "image";
            return to_python(j);
        },
        pyb::arg("image"), pyb::arg("reference"), pyb::arg("crop"), pyb::arg("normalise_by"));
}

}  // namespace snell::py
