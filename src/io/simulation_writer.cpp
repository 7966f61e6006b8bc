#include "odocal/io/simulation_writer.hpp"

#include "odocal/error.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/log_directory_output.hpp"
#include "odocal/io/output_file.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/stream_readers.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/io/trajectory_writer.hpp"
#include "odocal/io/vehicle_config_io.hpp"

namespace odocal {

void write_simulated_log(const sim::SimulatedDrive& drive, const sim::Scenario& scenario,
                         const std::filesystem::path& target) {
  LogDirectoryOutput output(target);
  const std::filesystem::path& directory = output.staging();

  write_vehicle_config(drive.nominal_vehicle, directory / "vehicle.yaml");
  write_text_file(directory / "wheels.csv", [&](TextBuffer& out) {
    const char* unit = enum_name(drive.wheel_unit);
    const bool forces = !drive.wheel_drive_force_n.empty();
    out.print("t,rl_{0},rr_{0}{1}\n", unit, forces ? ",drive_force_n" : "");
    const bool ticks = drive.wheel_unit == WheelUnit::kTicks;
    for (std::size_t k = 0; k < drive.wheel_t_s.size(); ++k) {
      if (ticks) {
        out.print("{:.4f},{:.0f},{:.0f}", drive.wheel_t_s[k], drive.wheel_rl[k], drive.wheel_rr[k]);
      } else {
        out.print("{:.4f},{:.9f},{:.9f}", drive.wheel_t_s[k], drive.wheel_rl[k], drive.wheel_rr[k]);
      }
      if (forces) out.print(",{:.1f}", drive.wheel_drive_force_n[k]);
      out.print("\n");
    }
  });
  write_text_file(directory / "gnss.csv", [&](TextBuffer& out) {
    // sigma_m must be positive in the log format: error-free fixes leave the column out.
    const bool has_sigma = drive.gnss_sigma_m > 0.0;
    const bool has_alt = !drive.gnss_alt.empty();
    const bool has_speed = !drive.gnss_speed_mps.empty();
    out.print("{}{}{}{}\n", drive.gnss_latlon ? "t,lat,lon" : "t,x,y", has_alt ? ",alt" : "",
              has_sigma ? ",sigma_m" : "", has_speed ? ",speed_mps" : "");
    const std::string sigma = has_sigma ? fmt::format(",{:.3f}", drive.gnss_sigma_m) : "";
    for (std::size_t k = 0; k < drive.gnss_t_s.size(); ++k) {
      const std::string alt = has_alt ? fmt::format(",{:.3f}", drive.gnss_alt[k]) : "";
      const std::string speed = has_speed ? fmt::format(",{:.4f}", drive.gnss_speed_mps[k]) : "";
      if (drive.gnss_latlon) {
        out.print("{:.4f},{:.9f},{:.9f}{}{}{}\n", drive.gnss_t_s[k], drive.gnss_a[k],
                  drive.gnss_b[k], alt, sigma, speed);
      } else {
        out.print("{:.4f},{:.4f},{:.4f}{}{}{}\n", drive.gnss_t_s[k], drive.gnss_a[k],
                  drive.gnss_b[k], alt, sigma, speed);
      }
    }
  });
  write_text_file(directory / "imu.csv", [&](TextBuffer& out) {
    out.print("t,ax,ay,wz\n");
    for (std::size_t k = 0; k < drive.imu.size(); ++k) {
      out.print("{:.4f},{:.6f},{:.6f},{:.7f}\n", drive.imu.t_s[k], drive.imu.ax_mps2[k],
                drive.imu.ay_mps2[k], drive.imu.wz_radps[k]);
    }
  });
  write_text_file(directory / "heading.csv", [&](TextBuffer& out) {
    out.print("t,heading\n");
    for (std::size_t k = 0; k < drive.heading.size(); ++k) {
      out.print("{:.4f},{:.7f}\n", drive.heading.t_s[k], drive.heading.heading_rad[k]);
    }
  });
  write_trajectory_csv(drive.truth, directory / "truth.csv");
  write_text_file(directory / "truth.yaml", [&](TextBuffer& out) {
    out.print("# The simulator's true parameters; estimators never read this file.\n");
    out.print("circumference_rl_m: {:.9f}\ncircumference_rr_m: {:.9f}\ntrack_width_m: {:.9f}\n",
              drive.true_params.circumference_rl_m, drive.true_params.circumference_rr_m,
              drive.true_params.track_width_m);
    out.print(
        "# rolling straight at a steady speed, drive slip against drag and rolling resistance "
        "included\nrolling_speed_mps: {:g}\nrolling_circumference_rl_m: {:.9f}\n"
        "rolling_circumference_rr_m: {:.9f}\n",
        drive.steady_rolling_speed_mps, drive.steady_rolling_circumference_m[0],
        drive.steady_rolling_circumference_m[1]);
    out.print("distance_m: {:.3f}\nduration_s: {:.3f}\nideal: {}\n", drive.distance_m,
              drive.wheel_t_s.empty() ? 0.0 : drive.wheel_t_s.back(), scenario.ideal);
    out.print("seeds: {{trajectory: {}, noise: {}}}\n", scenario.seeds.trajectory,
              scenario.seeds.noise);
  });
  write_output_file(directory / "scenario.yaml", scenario_to_yaml(scenario));
  output.commit();
}

Log simulated_log(const sim::SimulatedDrive& drive, bool with_truth) {
  const auto table = [](const char* file, std::vector<std::string> header,
                        std::vector<std::vector<double>> columns) {
    CsvTable out;
    out.file = file;
    out.header = std::move(header);
    out.columns = std::move(columns);
    out.line_of_row.resize(out.columns.front().size());
    for (std::size_t k = 0; k < out.line_of_row.size(); ++k) out.line_of_row[k] = k + 2;
    return out;
  };
  Log log;
  log.source = "simulation";
  log.vehicle = drive.nominal_vehicle;
  const std::string unit = enum_name(drive.wheel_unit);
  std::vector<std::string> wheel_header{"t", "rl_" + unit, "rr_" + unit};
  std::vector<std::vector<double>> wheel_columns{drive.wheel_t_s, drive.wheel_rl, drive.wheel_rr};
  if (!drive.wheel_drive_force_n.empty()) {
    wheel_header.emplace_back("drive_force_n");
    wheel_columns.push_back(drive.wheel_drive_force_n);
  }
  log.wheels =
      wheel_stream_from_table(table("wheels.csv", wheel_header, wheel_columns), log.vehicle);
  std::vector<std::string> gnss_header{"t", drive.gnss_latlon ? "lat" : "x",
                                       drive.gnss_latlon ? "lon" : "y"};
  std::vector<std::vector<double>> gnss_columns{drive.gnss_t_s, drive.gnss_a, drive.gnss_b};
  if (!drive.gnss_alt.empty()) {
    gnss_header.emplace_back("alt");
    gnss_columns.push_back(drive.gnss_alt);
  }
  if (!drive.gnss_speed_mps.empty()) {
    gnss_header.emplace_back("speed_mps");
    gnss_columns.push_back(drive.gnss_speed_mps);
  }
  log.gnss = gnss_stream_from_table(table("gnss.csv", gnss_header, gnss_columns));
  if (drive.gnss_sigma_m > 0.0) log.gnss.sigma_m.assign(log.gnss.size(), drive.gnss_sigma_m);
  log.imu = drive.imu;
  log.heading = drive.heading;
  if (with_truth) log.truth = drive.truth;
  return log;
}

}  // namespace odocal
