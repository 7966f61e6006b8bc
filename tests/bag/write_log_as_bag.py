#!/usr/bin/python3
"""Writes an odocal log directory as a car's ROS 1 bag, with ROS's own writer (Debian's
python3-rosbag), in the layout examples/bag-joint-states/topics.yaml maps:

  /joint_states  sensor_msgs/JointState  rear_left_wheel, rear_right_wheel positions (rad)
  /imu/data      sensor_msgs/Imu         gyro z, accelerations x/y, and the heading as orientation
  /fix           sensor_msgs/NavSatFix   lat/lon, diagonal covariance from sigma_m

The log must have wheels in rad, GNSS in lat/lon, and heading.csv on imu.csv's time stamps (as
`odocal simulate --wheel-output rad --gnss-output latlon` writes them).

Usage: write_log_as_bag.py LOG OUT.bag
"""
import csv
import math
import sys

import genpy
import rosbag
from sensor_msgs.msg import Imu, JointState, NavSatFix


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def stamp(t):
    nanoseconds = round(float(t) * 1e9)
    return genpy.Time(nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000)


def main():
    log, out = sys.argv[1], sys.argv[2]
    wheels, gnss = rows(f"{log}/wheels.csv"), rows(f"{log}/gnss.csv")
    imu, heading = rows(f"{log}/imu.csv"), rows(f"{log}/heading.csv")
    if [r["t"] for r in imu] != [r["t"] for r in heading]:
        sys.exit("heading.csv must have imu.csv's time stamps")
    with rosbag.Bag(out, "w", compression="lz4") as bag:
        for r in wheels:
            joints = JointState()
            joints.header.stamp = stamp(r["t"])
            joints.name = ["front_left_wheel", "rear_left_wheel", "rear_right_wheel"]
            joints.position = [0.0, float(r["rl_rad"]), float(r["rr_rad"])]
            bag.write("/joint_states", joints, joints.header.stamp)
        for r, h in zip(imu, heading):
            message = Imu()
            message.header.stamp = stamp(r["t"])
            message.header.frame_id = "imu_link"
            yaw = float(h["heading"])
            message.orientation.z = math.sin(yaw / 2)
            message.orientation.w = math.cos(yaw / 2)
            message.angular_velocity.z = float(r["wz"])
            message.linear_acceleration.x = float(r["ax"])
            message.linear_acceleration.y = float(r["ay"])
            message.linear_acceleration.z = 9.81
            bag.write("/imu/data", message, message.header.stamp)
        for r in gnss:
            fix = NavSatFix()
            fix.header.stamp = stamp(r["t"])
            fix.latitude, fix.longitude = float(r["lat"]), float(r["lon"])
            variance = float(r.get("sigma_m", 1.0)) ** 2
            fix.position_covariance = [variance, 0, 0, 0, variance, 0, 0, 0, 4 * variance]
            fix.position_covariance_type = NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN
            bag.write("/fix", fix, fix.header.stamp)


if __name__ == "__main__":
    main()
