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
        // Per pixel: the technique index of the largest sample (-1: none or unnamed) and the
        // share of the pixel's light it carries (Film::largest_sample_share; after the clamp).
        .def("technique_map",
             [](const PyFilm& f) {
                 pyb::array_t<int8_t> t({f.height, f.width});
                 auto v = t.mutable_unchecked<2>();
                 for (int y = 0; y < f.height; ++y)
                     for (int x = 0; x < f.width; ++x) v(y, x) = int8_t(f.result.film.largest_sample_technique(x, y));
                 return t;
             })
        // Per pixel: the luminance (Y) of its largest sample and its sample count, before the
        // clamp (the pixel's mean is its samples' sum over the count).
        .def("largest_sample_map",
             [](const PyFilm& f) {
                 pyb::array_t<float> s({f.height, f.width});
                 auto v = s.mutable_unchecked<2>();
                 for (int y = 0; y < f.height; ++y)
                     for (int x = 0; x < f.width; ++x) v(y, x) = float(f.result.film.largest_sample_y(x, y));
                 return s;
             })
        .def("samples_map",
             [](const PyFilm& f) {
                 pyb::array_t<uint64_t> s({f.height, f.width});
                 auto v = s.mutable_unchecked<2>();
                 for (int y = 0; y < f.height; ++y)
                     for (int x = 0; x < f.width; ++x) v(y, x) = f.result.film.samples(x, y);
                 return s;
             })
        .def("sample_share_map", [](const PyFilm& f) {
            pyb::array_t<float> s({f.height, f.width});
            auto v = s.mutable_unchecked<2>();
            for (int y = 0; y < f.height; ++y)
                for (int x = 0; x < f.width; ++x) v(y, x) = float(f.result.film.largest_sample_share(x, y));
            return s;
        });
}

}  // namespace snell::py
