#pragma once
// Where dead reckoning starts: the pose at the first wheel sample, from truth or from GNSS.

#include "odocal/data/log.hpp"

namespace odocal {

// Truth interpolated at t_s. Throws InsufficientDataError when truth does not cover t_s.
Pose2 start_pose_from_truth(const PoseStream& truth, double t_s);

struct GnssStartOptions {
  double window_s = 10.0;         // odometry and GNSS from the first wheel sample on
  double min_spread_m = 1.0;      // RMS distance from the centroid that gives a usable course
  double heading_window_s = 2.0;  // heading.csv fallback: line fit over this window
};

// Dead-reckons the first window_s with `params` from the origin and finds the rigid motion
// (rotation + translation, Umeyama) that best maps it onto the GNSS fixes of the window: that
// motion is the start pose. Unbiased by curvature, and it averages the fix noise. When either the
// odometry or the fixes spread less than min_spread_m (the vehicle barely moves), the position is
// the mean fix of the window and the heading comes from a line fit through heading.csv. Throws
// InsufficientDataError when neither works.
Pose2 start_pose_from_gnss(const Log& log, const OdometryParams& params,
                           const GnssStartOptions& options = {});

}  // namespace odocal
