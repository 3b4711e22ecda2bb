// PYBIND11_MODULE for snell._snell: the exception types, then each file's part.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "core/props.h"

PYBIND11_MODULE(_snell, m) {
    using namespace snell;
    using namespace snell::py;
    m.doc() = "snell's native half; import snell, not this (docs/python.md)";
    // A malformed scene or a bad parameter: the message is the command line's, "file:line: <element>: what".
    pyb::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
    bind_scene(m);
    bind_film(m);
    bind_render(m);
    bind_images(m);
    bind_compare(m);
}
