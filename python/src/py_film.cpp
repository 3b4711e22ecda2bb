// snell.Film: the film a render leaves. Its image buffer is what a rendered snell.Image views
// (the array's base), so no pixel is copied on the way to numpy.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"

namespace snell::py {

namespace {

// An H x W x 3 float32 view of `data`, kept alive by `owner` (the Film): base is the Film.
pyb::array_t<float> rgb_view(const PyFilm& f, const std::vector<float>& data, const pyb::object& owner) {
    const pyb::ssize_t w = f.width, h = f.height, fs = pyb::ssize_t(sizeof(float));
    return pyb::array_t<float>({h, w, pyb::ssize_t(3)}, {w * 3 * fs, 3 * fs, fs}, data.data(), owner);
}

// An H x W array of `value(film, x, y)` per pixel.
template <typename T, typename F>
pyb::array_t<T> pixel_map(const PyFilm& f, F value) {
    pyb::array_t<T> a({f.height, f.width});
    auto v = a.template mutable_unchecked<2>();
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) v(y, x) = value(f.result.film, x, y);
    return a;
}

}  // namespace

void bind_film(pyb::module_& m) {
    pyb::class_<PyFilm>(m, "Film", pyb::buffer_protocol())
        .def_buffer([](PyFilm& f) {
            const pyb::ssize_t w = f.width, h = f.height, fs = pyb::ssize_t(sizeof(float));
            return pyb::buffer_info(f.rgb.data(), fs, pyb::format_descriptor<float>::format(), 3,
                                    {h, w, pyb::ssize_t(3)}, {w * 3 * fs, 3 * fs, fs});
        })
        .def_readonly("width", &PyFilm::width)
        .def_readonly("height", &PyFilm::height)
        .def_property_readonly("stats", [](const PyFilm& f) { return to_python(f.stats); })
        .def_property_readonly("interrupted", [](const PyFilm& f) { return f.result.interrupted; })
        .def_property_readonly("layer_names", [](const PyFilm& f) { return f.result.layer_names; })
        .def_property_readonly("technique_names", [](const PyFilm& f) { return f.result.technique_names; })
        .def(
            "layer",
            [](pyb::object self, size_t k) {
                const PyFilm& f = self.cast<const PyFilm&>();
                if (k < 1 || k > f.layers.size())
                    throw pyb::index_error("debug layer " + std::to_string(k) + " of " +
                                           std::to_string(f.layers.size()));
                return rgb_view(f, f.layers[k - 1], self);
            },
            pyb::arg("k"))
        // Per pixel: the technique index of the largest sample (-1: none or unnamed), its
        // luminance (Y) before the clamp, the share of the pixel's light it carries
        // (Film::largest_sample_share; after the clamp), and the pixel's sample count.
        .def("technique_map",
             [](const PyFilm& f) {
                 return pixel_map<int8_t>(
                     f, [](const Film& m, int x, int y) { return int8_t(m.largest_sample_technique(x, y)); });
             })
        .def("largest_sample_map",
             [](const PyFilm& f) {
                 return pixel_map<float>(f,
                                         [](const Film& m, int x, int y) { return float(m.largest_sample_y(x, y)); });
             })
        .def("samples_map",
             [](const PyFilm& f) {
                 return pixel_map<uint64_t>(f, [](const Film& m, int x, int y) { return m.samples(x, y); });
             })
        .def("sample_share_map", [](const PyFilm& f) {
            return pixel_map<float>(f, [](const Film& m, int x, int y) { return float(m.largest_sample_share(x, y)); });
        });
}

}  // namespace snell::py
