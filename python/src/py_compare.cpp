// snell.compare: `snell compare` in this process (apps/cmd_compare.cpp, the same code), its
// report.json back as a dict.
#include <pybind11/stl.h>

#include <csignal>
#include <fstream>

#include "app_common.h"
#include "bindings.h"
#include "commands.h"

namespace snell::py {

namespace {

// cmd_compare installs the command line's Ctrl-C handler and leaves SIGINT at its default: put
// Python's handler back whichever way it ends, so that Ctrl-C still raises KeyboardInterrupt.
class KeepSigint {
public:
    KeepSigint() { sigaction(SIGINT, nullptr, &m_saved); }
    ~KeepSigint() { sigaction(SIGINT, &m_saved, nullptr); }

private:
    struct sigaction m_saved {};
};

}  // namespace

void bind_compare(pyb::module_& m) {
    // Returns (report.json as a dict, interrupted).
    m.def(
        "compare",
        [](const CompareOptions& opt) {
            {
                pyb::gil_scoped_release nogil;
                KeepSigint keep;
                g_cancel = false;  // a Ctrl-C of an earlier compare is not this one's
                cmd_compare(opt);
            }
            std::ifstream in(std::filesystem::path(opt.out_dir) / "report.json");
            nlohmann::json j;
            if (!(in >> j)) throw std::runtime_error("compare: cannot read " + opt.out_dir + "/report.json");
            return pyb::make_tuple(to_python(j), g_cancel.load());
        },
        pyb::arg("options"));

    pyb::class_<CompareOptions>(m, "CompareOptions")
        .def(pyb::init<>())
        .def_readwrite("scene", &CompareOptions::scene)
        .def_readwrite("integrators", &CompareOptions::integrators)
        .def_readwrite("time", &CompareOptions::time)
        .def_readwrite("out_dir", &CompareOptions::out_dir)
        .def_readwrite("reference_file", &CompareOptions::reference_file)
        .def_readwrite("reference_offset", &CompareOptions::reference_offset)
        .def_readwrite("reference_integrator", &CompareOptions::reference_integrator)
        .def_readwrite("reference_spp", &CompareOptions::reference_spp)
        .def_readwrite("reference_time", &CompareOptions::reference_time)
        .def_readwrite("defines", &CompareOptions::defines)
        .def_readwrite("crops", &CompareOptions::crops)
        .def_readwrite("threads", &CompareOptions::threads)
        .def_readwrite("seed", &CompareOptions::seed)
        .def_readwrite("exposure", &CompareOptions::exposure)
        .def_readwrite("convergence_steps", &CompareOptions::convergence_steps)
        .def_readwrite("error_max", &CompareOptions::error_max)
        .def_readwrite("quiet", &CompareOptions::quiet);
}

}  // namespace snell::py
