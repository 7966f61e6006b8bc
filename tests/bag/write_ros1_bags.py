#!/usr/bin/python3
"""Writes small ROS 1 bags with ROS's own writer (Debian's python3-rosbag) for the bag reader
tests: the same known messages stored uncompressed, bz2 and lz4 (roslz4) in OUT_DIR.

Values are functions of the message number k so that the C++ test checks them exactly."""
import sys

import genpy
import rosbag
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, NavSatFix
from std_msgs.msg import Float64

COUNT = 50  # messages per topic; --count N for smaller bags (the fuzz corpus)


def stamp(k):
    return genpy.Time(1000 + k // 10, (k % 10) * 100_000_000)


def write(path, compression, count):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=2048) as bag:
        for k in range(count):
            imu = Imu()
            imu.header.stamp = stamp(k)
            imu.header.frame_id = "imu_link"
            imu.angular_velocity.z = 0.01 * k
            imu.linear_acceleration.x = float(k)
            bag.write("/imu/data", imu, stamp(k))
            joints = JointState()
            joints.header.stamp = stamp(k)
            joints.name = ["rear_left_wheel", "rear_right_wheel"]
            joints.position = [0.1 * k, 0.2 * k]
            bag.write("/joint_states", joints, stamp(k))
            if k % 5 == 0:
                fix = NavSatFix()
                fix.header.stamp = stamp(k)
                fix.latitude = 48.0 + 1e-5 * k
                fix.longitude = 8.5
                fix.position_covariance = [0.25, 0, 0, 0, 0.25, 0, 0, 0, 1.0]
                fix.position_covariance_type = 2
                bag.write("/fix", fix, stamp(k))
            heading = Float64()
            heading.data = (90.0 - 2.0 * k) % 360.0  # compass degrees: 90 (east) turning left
            bag.write("/gnss/heading_deg", heading, stamp(k))
            odom = Odometry()
            odom.header.stamp = stamp(k)
            odom.child_frame_id = "base_link"
            odom.twist.twist.linear.x = 1.5
            odom.twist.twist.angular.z = -0.25
            bag.write("/odom", odom, stamp(k))


def main():
    out_dir = sys.argv[1]
    count = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[2] == "--count" else COUNT
    for compression in ("none", "bz2", "lz4"):
        write(f"{out_dir}/written_{compression}.bag", compression, count)


if __name__ == "__main__":
    main()
