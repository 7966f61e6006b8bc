// Dead-reckons one step with the installed library; exits 0 when the result is right.
#include <cmath>
#include <cstdio>

#include "odocal/error.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/model/odometry_model.hpp"

int main() {
  const odocal::Pose2 pose =
      odocal::predict_pose(odocal::Pose2::Zero(), {1.0, 1.0}, {2.0, 2.0, 1.6});
  try {
    odocal::read_log("/nonexistent/odocal/log");
    return 1;
  } catch (const odocal::InputError&) {
  }
  std::printf("consumer: x = %.3f\n", pose.x());
  return std::abs(pose.x() - 2.0) < 1e-12 ? 0 : 1;
}
