// module.cpp - the extension module fracarm._fracarm (issue 20): libfrac's
// objects, model documents, the gap diagnosis, the fracdesign verbs and
// gap-bench's scoring. The Python package (python/fracarm) wraps it.
#include <pybind11/pybind11.h>

#include "fracbench/armctrl_controller.hpp"

namespace py = pybind11;

void bind_libfrac(py::module_& m);
void bind_gap(py::module_& m);
void bind_design(py::module_& m);
void bind_bench(py::module_& m);

PYBIND11_MODULE(_fracarm, m)
{
    m.doc() = "fracarm's compiled core: libfrac, fracdesign models, gap diagnosis and verbs";
    // the PLC's controller kinds (gap.closed_loop.controller kind "armctrl"), as gap-plc has them
    fracbench::register_armctrl_controller();
    bind_libfrac(m);
    bind_gap(m);
    bind_design(m);
    bind_bench(m);
}
