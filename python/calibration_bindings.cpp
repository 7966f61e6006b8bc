// Calibration from Python: every method, options as a dict (the `--config` file's keys, checked
// by the same reader), the summary as an object whose JSON form is the CLI's.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/options/enum_names.hpp"

namespace py = pybind11;

namespace odocal::python {
namespace {

// One calibration's outcome with the configuration it ran with.
struct CalibrationResult {
  AnyCalibrationSummary summary;
  CalibrationConfig config;

  const CalibrationSummary& core() const {
    return std::visit([](const auto& s) -> const CalibrationSummary& { return s; }, summary);
  }
  py::object as_dict() const {
    const std::string text = summary_to_json(summary, config).dump();
    return py::module_::import("json").attr("loads")(text);
  }
};

CalibrationConfig config_from(const std::optional<std::string>& method, const py::object& options) {
  CalibrationConfig config;
  if (!options.is_none()) {
    // JSON is YAML: the dict goes through the --config reader, with its checks and messages.
    const std::string text = py::module_::import("json").attr("dumps")(options).cast<std::string>();
    config = parse_calibration_config(text, "options");
  }
  if (method) {
    const auto parsed = parse_enum<CalibrationMethod>(*method);
    if (!parsed) throw py::value_error("unknown method '" + *method + "'");
    config.method = *parsed;
  }
  return config;
}

}  // namespace

void bind_calibration(py::module_& m) {
  py::class_<CalibrationResult>(m, "CalibrationSummary", "A calibration's outcome")
      .def_property_readonly(
          "method",
          [](const CalibrationResult& r) { return std::string(enum_name(r.core().method)); })
      .def_property_readonly(
          "circumference_rl_m",
          [](const CalibrationResult& r) { return r.core().estimate.circumference_rl_m; })
      .def_property_readonly(
          "circumference_rr_m",
          [](const CalibrationResult& r) { return r.core().estimate.circumference_rr_m; })
      .def_property_readonly(
          "track_width_m",
          [](const CalibrationResult& r) { return r.core().estimate.track_width_m; })
      .def_property_readonly(
          "tyre_model",
          [](const CalibrationResult& r) {
            const TyreModel& t = r.core().tyre_model;
            py::dict out;
            for (const TyreCoefficient& coefficient : kTyreCoefficients)
              out[coefficient.key] = t.*(coefficient.member);
            return out;
          },
          "the condition-dependent circumference's coefficients (all zero: plain model; "
          "docs/tyre-model.md)")
      .def_property_readonly(
          "antenna_m",
          [](const CalibrationResult& r) -> std::optional<std::pair<double, double>> {
            const auto* batch = std::get_if<BatchSummary>(&r.summary);
            const auto place = batch ? fitted_antenna_place(*batch) : std::nullopt;
            if (!place) return std::nullopt;
            return std::make_pair(place->x(), place->y());
          },
          "where the batch found the GNSS antenna, (forward, left) of the rear axle's centre in "
          "metres; None where it held it (vehicle.yaml's gnss_x_m, gnss_y_m, or the options')")
      .def_property_readonly("sigma_rl_m",
                             [](const CalibrationResult& r) { return r.core().sigma_rl_m(); })
      .def_property_readonly("sigma_rr_m",
                             [](const CalibrationResult& r) { return r.core().sigma_rr_m(); })
      .def_property_readonly(
          "covariance",
          [](const CalibrationResult& r) {
            const Eigen::Matrix2d& c = r.core().covariance;
            py::array_t<double> out({2, 2});
            auto view = out.mutable_unchecked<2>();
            for (int i = 0; i < 2; ++i)
              for (int j = 0; j < 2; ++j) view(i, j) = c(i, j);
            return out;
          },
          "covariance of [c_RL, c_RR], m^2")
      .def_property_readonly(
          "termination",
          [](const CalibrationResult& r) { return std::string(enum_name(r.core().termination)); })
      .def_property_readonly("usable", [](const CalibrationResult& r) { return r.core().usable(); })
      .def_property_readonly("message", [](const CalibrationResult& r) { return r.core().message; })
      .def_property_readonly("note", [](const CalibrationResult& r) { return r.core().note; })
      .def("brief_report",
           [](const CalibrationResult& r) {
             return std::visit([](const auto& s) { return s.brief_report(); }, r.summary);
           })
      .def("full_report",
           [](const CalibrationResult& r) {
             return std::visit([](const auto& s) { return s.full_report(); }, r.summary);
           })
      .def("to_dict", &CalibrationResult::as_dict,
           "everything, as `odocal calibrate --json` writes it")
      .def("__repr__", [](const CalibrationResult& r) {
        return std::visit([](const auto& s) { return s.brief_report(); }, r.summary);
      });

  m.def(
      "calibrate",
      [](const Log& log, std::optional<std::string> method, py::object options) {
        CalibrationResult result{{}, config_from(method, options)};
        py::gil_scoped_release release;
        result.summary = calibrate(log, result.config);
        return result;
      },
      py::arg("log"), py::arg("method") = py::none(), py::arg("options") = py::none(),
      "Calibrate `log` with `method` (iterative, fixed-p, augmented, batch) and `options`, a dict "
      "with the keys of `odocal calibrate --config` (odocal calibrate --print-config lists them)");
}

}  // namespace odocal::python
