// The log as Python sees it: streams whose columns are NumPy arrays viewing the C++ vectors (no
// copy; each array keeps its log alive), and the vehicle's nominal parameters.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.hpp"
#include "odocal/data/log.hpp"

namespace py = pybind11;

namespace odocal::python {

py::array view(const std::vector<double>& column, py::handle owner) {
  return py::array(py::dtype::of<double>(), {static_cast<py::ssize_t>(column.size())},
                   {static_cast<py::ssize_t>(sizeof(double))}, column.data(), owner);
}

namespace {

// A column attribute: a read-only view of member `column` of the stream at `stream`.
template <class Stream, class Owner>
void column(py::class_<Stream, Owner>& cls, const char* name, std::vector<double> Stream::*member,
            const char* doc) {
  cls.def_property_readonly(
      name,
      [member](py::object self) {
        const Stream& stream = self.cast<const Stream&>();
        py::array out = view(stream.*member, self);
        out.attr("flags").attr("writeable") = false;
        return out;
      },
      doc);
}

// A sensor's place in vehicle.yaml, one coordinate of it (None where unstated).
auto mounted_coordinate(std::optional<Eigen::Vector2d> VehicleConfig::*place, int coordinate) {
  return [place, coordinate](const VehicleConfig& v) -> std::optional<double> {
    if (!(v.*place)) return std::nullopt;
    return (*(v.*place))(coordinate);
  };
}

}  // namespace

void bind_log(py::module_& m) {
  py::class_<VehicleConfig>(m, "VehicleConfig", "Nominal vehicle (vehicle.yaml)")
      .def_readonly("vehicle_id", &VehicleConfig::vehicle_id)
      .def_readonly("track_width_m", &VehicleConfig::track_width_m)
      .def_readonly("circumference_rl_m", &VehicleConfig::circumference_rl_m)
      .def_readonly("circumference_rr_m", &VehicleConfig::circumference_rr_m)
      .def_readonly("ticks_per_rev", &VehicleConfig::ticks_per_rev)
      .def_readonly("wheelbase_m", &VehicleConfig::wheelbase_m)
      .def_property_readonly("imu_x_m", mounted_coordinate(&VehicleConfig::imu_position_m, 0))
      .def_property_readonly("imu_y_m", mounted_coordinate(&VehicleConfig::imu_position_m, 1))
      .def_property_readonly("gnss_x_m", mounted_coordinate(&VehicleConfig::gnss_position_m, 0))
      .def_property_readonly("gnss_y_m", mounted_coordinate(&VehicleConfig::gnss_position_m, 1));

  py::class_<WheelStream, std::unique_ptr<WheelStream, py::nodelete>> wheels(
      m, "WheelStream", "Rear wheel revolution increments (paper eq. 2)");
  column(wheels, "t_s", &WheelStream::t_s, "sample times, s");
  column(wheels, "rev_rl", &WheelStream::rev_rl, "RL revolutions since the previous sample");
  column(wheels, "rev_rr", &WheelStream::rev_rr, "RR revolutions since the previous sample");
  column(wheels, "drive_force_n", &WheelStream::drive_force_n,
         "the tyres' total longitudinal force, N (empty when absent)");
  wheels.def("__len__", &WheelStream::size);

  py::class_<GnssStream, std::unique_ptr<GnssStream, py::nodelete>> gnss(
      m, "GnssStream", "GNSS fixes in local ENU metres");
  column(gnss, "t_s", &GnssStream::t_s, "fix times, s");
  column(gnss, "x_m", &GnssStream::x_m, "east, m");
  column(gnss, "y_m", &GnssStream::y_m, "north, m");
  column(gnss, "altitude_m", &GnssStream::altitude_m, "altitude, m (empty when absent)");
  column(gnss, "sigma_m", &GnssStream::sigma_m, "horizontal 1-sigma, m (empty when absent)");
  column(gnss, "speed_mps", &GnssStream::speed_mps, "Doppler speed, m/s (empty when absent)");
  gnss.def("__len__", &GnssStream::size);

  py::class_<ImuStream, std::unique_ptr<ImuStream, py::nodelete>> imu(
      m, "ImuStream", "Body-frame IMU (forward-left-up)");
  column(imu, "t_s", &ImuStream::t_s, "sample times, s");
  column(imu, "ax_mps2", &ImuStream::ax_mps2, "forward acceleration, m/s^2");
  column(imu, "ay_mps2", &ImuStream::ay_mps2, "left acceleration, m/s^2");
  column(imu, "wz_radps", &ImuStream::wz_radps, "yaw rate, rad/s (CCW)");
  imu.def("__len__", &ImuStream::size);

  py::class_<HeadingStream, std::unique_ptr<HeadingStream, py::nodelete>> heading(
      m, "HeadingStream", "Absolute heading, rad CCW from east");
  column(heading, "t_s", &HeadingStream::t_s, "sample times, s");
  column(heading, "heading_rad", &HeadingStream::heading_rad, "heading, rad");
  heading.def("__len__", &HeadingStream::size);

  // Streams are returned by reference with the log as their keeper (keep_alive 0 <- 1).
  py::class_<Log, std::shared_ptr<Log>>(m, "Log", "A log as read or simulated")
      .def_readonly("source", &Log::source)
      .def_readonly("vehicle", &Log::vehicle)
      .def_property_readonly(
          "wheels", [](Log& log) { return &log.wheels; },
          py::return_value_policy::reference_internal)
      .def_property_readonly(
          "gnss", [](Log& log) { return &log.gnss; }, py::return_value_policy::reference_internal)
      .def_property_readonly(
          "imu", [](Log& log) { return log.imu ? &*log.imu : nullptr; },
          py::return_value_policy::reference_internal)
      .def_property_readonly(
          "heading", [](Log& log) { return log.heading ? &*log.heading : nullptr; },
          py::return_value_policy::reference_internal);
}

}  // namespace odocal::python
