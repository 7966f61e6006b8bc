#include "odocal/io/trajectory_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

}  // namespace

TrajectoryFileWriter::TrajectoryFileWriter(const std::filesystem::path& path,
                                           TrajectoryFormat format)
    : out_(path), format_(format) {
  if (format_ == TrajectoryFormat::kCsv)
    fmt::format_to(std::back_inserter(buffer_), "t,x,y,heading\n");
}

void TrajectoryFileWriter::add(double t_s, const Pose2& pose) {
  const double heading = wrap_angle(pose.z());
  if (format_ == TrajectoryFormat::kCsv) {
    fmt::format_to(std::back_inserter(buffer_), "{:.6f},{:.6f},{:.6f},{:.9f}\n", t_s, pose.x(),
                   pose.y(), heading);
  } else {
    const double half_yaw = 0.5 * heading;
    fmt::format_to(std::back_inserter(buffer_), "{:.6f} {:.6f} {:.6f} 0 0 0 {:.9f} {:.9f}\n", t_s,
                   pose.x(), pose.y(), std::sin(half_yaw), std::cos(half_yaw));
  }
  if (buffer_.size() >= kFlushBytes) flush();
}

void TrajectoryFileWriter::commit() {
  flush();
  out_.commit();
}

void TrajectoryFileWriter::flush() {
  out_.write({buffer_.data(), buffer_.size()});
  buffer_.clear();
}

void write_trajectory_csv(const PoseStream& trajectory, const std::filesystem::path& path) {
  TrajectoryFileWriter out(path, TrajectoryFormat::kCsv);
  for (std::size_t k = 0; k < trajectory.size(); ++k)
    out.add(trajectory.t_s[k], trajectory.pose[k]);
  out.commit();
}

void write_trajectory_tum(const PoseStream& trajectory, const std::filesystem::path& path) {
  TrajectoryFileWriter out(path, TrajectoryFormat::kTum);
  for (std::size_t k = 0; k < trajectory.size(); ++k)
    out.add(trajectory.t_s[k], trajectory.pose[k]);
  out.commit();
}

}  // namespace odocal
