#include "odocal/io/trajectory_writer.hpp"

#include <fmt/os.h>

#include <cmath>

#include "odocal/error.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
void write_trajectory_csv(const PoseStream& trajectory, const std::filesystem::path& path) {
  write_text_file(path, [&](TextBuffer& out) {
    out.print("t,x,y,heading\n");
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      const Pose2& pose = trajectory.pose[k];
      out.print("{:.6f},{:.6f},{:.6f},{:.9f}\n", trajectory.t_s[k], pose.x(), pose.y(),
                wrap_angle(pose.z()));
    }
  });
}

void write_trajectory_tum(const PoseStream& trajectory, const std::filesystem::path& path) {
  write_text_file(path, [&](TextBuffer& out) {
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      const Pose2& pose = trajectory.pose[k];
      const double half_yaw = 0.5 * wrap_angle(pose.z());
      out.print("{:.6f} {:.6f} {:.6f} 0 0 0 {:.9f} {:.9f}\n", trajectory.t_s[k], pose.x(), pose.y(),
                std::sin(half_yaw), std::cos(half_yaw));
    }
  });
}

}  // namespace odocal
