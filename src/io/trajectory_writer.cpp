#include "odocal/io/trajectory_writer.hpp"

#include <fmt/os.h>

#include <cmath>

#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

// fmt::output_file throws std::system_error; report it as odocal::Error naming the file.
template <typename WriteRows>
void write_text_file(const std::filesystem::path& path, WriteRows&& write_rows) {
  try {
    auto out = fmt::output_file(path.string());
    write_rows(out);
    out.close();
  } catch (const std::system_error& e) {
    throw Error("cannot write " + path.string() + ": " + e.code().message());
  }
}

}  // namespace

void write_trajectory_csv(const PoseStream& trajectory, const std::filesystem::path& path) {
  write_text_file(path, [&](fmt::ostream& out) {
    out.print("t,x,y,heading\n");
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      const Pose2& pose = trajectory.pose[k];
      out.print("{:.6f},{:.6f},{:.6f},{:.9f}\n", trajectory.t_s[k], pose.x(), pose.y(),
                wrap_angle(pose.z()));
    }
  });
}

void write_trajectory_tum(const PoseStream& trajectory, const std::filesystem::path& path) {
  write_text_file(path, [&](fmt::ostream& out) {
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      const Pose2& pose = trajectory.pose[k];
      const double half_yaw = 0.5 * wrap_angle(pose.z());
      out.print("{:.6f} {:.6f} {:.6f} 0 0 0 {:.9f} {:.9f}\n", trajectory.t_s[k], pose.x(), pose.y(),
                std::sin(half_yaw), std::cos(half_yaw));
    }
  });
}

}  // namespace odocal
