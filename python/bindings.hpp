#pragma once
// Pieces of the `odocal` Python module (python/odocal_module.cpp assembles them).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

namespace odocal::python {

// A NumPy array viewing `column` without a copy; `owner` keeps the data alive.
pybind11::array view(const std::vector<double>& column, pybind11::handle owner);

void bind_log(pybind11::module_& m);
void bind_calibration(pybind11::module_& m);

}  // namespace odocal::python
