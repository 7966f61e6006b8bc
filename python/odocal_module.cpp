// The `odocal` Python module (docs/python.md): read or simulate a log, diagnose it, calibrate it
// with any method, validate the result on held-out windows, dead-reckon it. Errors arrive as
// Python exceptions with odocal's one-line messages (InputError -> ValueError).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>

#include "bindings.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/drift_validation.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/tick_dequantisation.hpp"
#include "odocal/io/log_doctor.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace py = pybind11;
using namespace odocal;

namespace {

py::list findings_list(const Diagnosis& diagnosis) {
  py::list out;
  for (const Finding& f : diagnosis.findings) {
    py::dict d;
    d["check"] = f.check;
    d["severity"] = severity_name(f.severity);
    d["what"] = f.what;
    d["evidence"] = f.evidence;
    d["cause"] = f.cause;
    d["fix"] = f.fix;
    out.append(d);
  }
  return out;
}

py::dict statistics(const DriftStatistics& s) {
  py::dict d;
  d["windows"] = s.windows;
  d["median_drift_percent"] = s.median_drift_percent;
  d["p95_drift_percent"] = s.p95_drift_percent;
  d["median_end_error_m"] = s.median_end_error_m;
  d["p95_end_error_m"] = s.p95_end_error_m;
  return d;
}

OdometryParams params_of(const Log& log, const py::object& params) {
  if (params.is_none()) return log.vehicle.nominal_params();
  if (py::hasattr(params, "circumference_rl_m")) {
    return {params.attr("circumference_rl_m").cast<double>(),
            params.attr("circumference_rr_m").cast<double>(),
            params.attr("track_width_m").cast<double>()};
  }
  const auto t = params.cast<std::tuple<double, double, double>>();
  return {std::get<0>(t), std::get<1>(t), std::get<2>(t)};
}

// The tyre model that goes with `params`: a calibration's own, vehicle.yaml's for the nominal
// parameters (None), plain for explicit numbers.
TyreModel tyre_of(const Log& log, const py::object& params) {
  if (params.is_none()) return log.vehicle.tyre_model.value_or(TyreModel{});
  if (!py::hasattr(params, "tyre_model")) return {};
  const auto k = params.attr("tyre_model").cast<py::dict>();
  TyreModel model;
  for (const TyreCoefficient& coefficient : kTyreCoefficients)
    model.*(coefficient.member) = k[coefficient.key].cast<double>();
  return model;
}

}  // namespace

PYBIND11_MODULE(odocal, m) {
  m.doc() = "Offline calibration of a vehicle's wheel odometry (docs/python.md)";
  // pybind11 tries the translators last registered first: the most derived error goes last.
  py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<InsufficientDataError>(m, "InsufficientDataError", PyExc_RuntimeError);
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  python::bind_log(m);
  python::bind_calibration(m);

  m.def(
      "read_log",
      [](const std::filesystem::path& directory, bool truth) {
        LogReadOptions options;
        options.read_truth = truth;
        return std::make_shared<Log>(read_log(directory, options));
      },
      py::arg("directory"), py::arg("truth") = false, "Read a log directory (docs/log-format.md)");

  m.def(
      "simulate",
      [](const std::string& scenario_name, std::optional<bool> ideal, std::optional<int> laps,
         std::optional<std::uint64_t> seed, std::optional<double> wear_rl_mm,
         std::optional<double> wear_rr_mm) {
        sim::Scenario scenario = load_scenario(scenario_name);
        if (ideal) scenario.ideal = *ideal;
        if (laps) scenario.route.laps = *laps;
        if (seed) scenario.seeds.noise = *seed;
        if (wear_rl_mm) scenario.vehicle.wear_rl_mm = *wear_rl_mm;
        if (wear_rr_mm) scenario.vehicle.wear_rr_mm = *wear_rr_mm;
        auto log = std::make_shared<Log>(simulated_log(sim::simulate(scenario)));
        log->source = "simulation: " + scenario_name;
        return log;
      },
      py::arg("scenario") = "circuit", py::arg("ideal") = py::none(), py::arg("laps") = py::none(),
      py::arg("seed") = py::none(), py::arg("wear_rl_mm") = py::none(),
      py::arg("wear_rr_mm") = py::none(),
      "Simulate a built-in scenario (circuit, parking, urban, robot) or a scenario YAML file");

  m.def(
      "doctor", [](const Log& log) { return findings_list(diagnose_log(log)); }, py::arg("log"),
      "The doctor's findings on a log in memory, as dicts (check, severity, what, evidence, cause, "
      "fix)");
  m.def(
      "doctor",
      [](const std::filesystem::path& directory) { return findings_list(doctor_log(directory)); },
      py::arg("directory"), "The doctor's findings on a log directory, raw-file checks included");

  m.def(
      "validate",
      [](const Log& given, py::object params, double window_s, double min_distance_m, double step_s,
         double tick_smoothing_s) {
        // The antenna where the calibration found it, as `odocal validate` takes it.
        std::optional<Log> with_antenna;
        if (py::hasattr(params, "antenna_m") && !params.attr("antenna_m").is_none()) {
          const auto [x, y] = params.attr("antenna_m").cast<std::pair<double, double>>();
          VehicleConfig vehicle = given.vehicle;
          if (adopt_found_antenna(vehicle, Eigen::Vector2d(x, y))) {
            with_antenna = given;
            with_antenna->vehicle = std::move(vehicle);
          }
        }
        const Log& input = with_antenna ? *with_antenna : given;
        const OdometryParams calibrated = params_of(input, params);
        CalibrationOptions options;
        options.reference.mode = ReferenceMode::kSmoother;
        LogPreparation prepared_by;
        const std::optional<Log> prepared = prepare_log(input, options, prepared_by);
        const Log& log = prepared ? *prepared : input;
        DriftValidationOptions drift;
        drift.window_s = window_s;
        drift.step_s = step_s;
        drift.min_window_distance_m = min_distance_m;
        drift.tick_smoothing_s = tick_smoothing_s;
        const OdometryParams nominal = log.vehicle.nominal_params();
        const DriftValidation v =
            validate_drift(with_tyre_model(log, nominal, tyre_of(log, py::none())),
                           with_tyre_model(log, calibrated, tyre_of(input, params)),
                           compute_reference(log, options.reference, ReferenceCovariance::kKeep),
                           nominal, calibrated, drift);
        py::dict out;
        out["nominal"] = statistics(v.nominal_statistics);
        out["calibrated"] = statistics(v.calibrated_statistics);
        py::dict reference;
        reference["median_end_error_m"] = v.reference->median_end_error_m;
        reference["median_drift_percent"] = v.reference->median_drift_percent;
        out["reference_uncertainty"] = reference;
        py::list windows;
        for (std::size_t i = 0; i < v.nominal.size(); ++i) {
          py::dict w;
          w["start_s"] = v.nominal[i].start_s;
          w["distance_m"] = v.nominal[i].distance_m;
          w["nominal_end_error_m"] = v.nominal[i].end_error_m;
          w["calibrated_end_error_m"] = v.calibrated[i].end_error_m;
          w["reference_rms_m"] = v.reference->rms_m[i];
          windows.append(w);
        }
        out["windows"] = windows;
        return out;
      },
      py::arg("log"), py::arg("params"), py::arg("window_s") = 60.0,
      py::arg("min_distance_m") = 20.0, py::arg("step_s") = 0.0,
      py::arg("tick_smoothing_s") = kDefaultTickSmoothingS,
      "Held-out drift of nominal and calibrated parameters (a CalibrationSummary or "
      "(c_RL, c_RR, track) in metres), as `odocal validate`");

  m.def(
      "dead_reckon",
      [](const Log& input, py::object params, std::tuple<double, double, double> start,
         bool prepare, double tick_smoothing_s) {
        const OdometryParams at = params_of(input, params);
        // Prepared as `odocal deadreckon` prepares it: the tyre model was fitted to the prepared
        // accelerometer (its forward offset taken out), and takes ax again here.
        LogPreparation prepared_by;
        const std::optional<Log> prepared =
            prepare ? prepare_log(input, CalibrationOptions{}, prepared_by, false) : std::nullopt;
        const Log& log = prepared ? *prepared : input;
        const PoseStream poses = dead_reckon(
            dequantised_ticks(with_tyre_model(log, at, tyre_of(input, params)), tick_smoothing_s),
            at, Pose2(std::get<0>(start), std::get<1>(start), std::get<2>(start)),
            // Without a reference, the pose is carried across a wheel gap.
            [](double, const Pose2& carried) { return carried; });
        py::array_t<double> t(poses.size()), x(poses.size()), y(poses.size()), yaw(poses.size());
        for (std::size_t k = 0; k < poses.size(); ++k) {
          t.mutable_at(k) = poses.t_s[k];
          x.mutable_at(k) = poses.pose[k].x();
          y.mutable_at(k) = poses.pose[k].y();
          yaw.mutable_at(k) = poses.pose[k].z();
        }
        py::dict out;
        out["t_s"] = t;
        out["x_m"] = x;
        out["y_m"] = y;
        out["yaw_rad"] = yaw;
        out["prepared"] = prepared_by.describe();
        return out;
      },
      py::arg("log"), py::arg("params") = py::none(),
      py::arg("start") = std::make_tuple(0.0, 0.0, 0.0), py::arg("prepare") = true,
      py::arg("tick_smoothing_s") = kDefaultTickSmoothingS,
      "Dead-reckon the wheels from `start` (x, y, yaw) with `params` (default: nominal), with its "
      "tyre model (a calibration's, or vehicle.yaml's for the nominal), the log prepared as "
      "`odocal deadreckon` prepares it (prepare=False: as it is)");
}
