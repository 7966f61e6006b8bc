#pragma once
// Writes trajectories for users' tools: odocal CSV (t,x,y,heading) and TUM
// ("timestamp tx ty tz qx qy qz qw", planar: z = 0, rotation about +z by the heading).

#include <fmt/format.h>

#include <filesystem>

#include "odocal/data/log.hpp"
#include "odocal/io/output_file.hpp"

namespace odocal {

enum class TrajectoryFormat { kCsv, kTum };

// A trajectory written pose by pose (a long log's, never held whole), whole or not at all.
class TrajectoryFileWriter {
 public:
  TrajectoryFileWriter(const std::filesystem::path& path, TrajectoryFormat format);
  void add(double t_s, const Pose2& pose);
  void commit();

 private:
  void flush();
  OutputFileStream out_;
  TrajectoryFormat format_;
  fmt::memory_buffer buffer_;
};

void write_trajectory_csv(const PoseStream& trajectory, const std::filesystem::path& path);
void write_trajectory_tum(const PoseStream& trajectory, const std::filesystem::path& path);

}  // namespace odocal
