#!/usr/bin/python3
"""Writes an odocal log directory as a car's ROS 1 bag, with ROS's own writer (Debian's
python3-rosbag), in the layout examples/bag-joint-states/topics.yaml maps:

  /joint_states  sensor_msgs/JointState  rear_left_wheel, rear_right_wheel positions (rad)
  /imu/data      sensor_msgs/Imu         gyro z, accelerations x/y, and the heading as orientation
  /fix           sensor_msgs/NavSatFix   lat/lon (altitude NaN without an alt column), diagonal
                                         covariance from sigma_m

With a drive_force_n column in wheels.csv, also
  /drive_force   std_msgs/Float64        the tyres' force (N), at its row's time as the bag's
                                         record time (the message has no header)

The log must have wheels in rad, GNSS in lat/lon, and heading.csv on imu.csv's time stamps (as
`odocal simulate --wheel-output rad --gnss-output latlon` writes them).

With --twist, the wheels go out as a robot's drive controller publishes them instead:
  /odom          nav_msgs/Odometry       twist: speed and yaw rate from the wheel increments
                                         (ticks or rad) with vehicle.yaml's nominal geometry
and the heading only when heading.csv shares imu.csv's stamps.

With --tf, the sensors' places go out as tf's static transforms, as a car's URDF publishes them:
  /tf_static     tf2_msgs/TFMessage      base_link -> chassis (0.3 m up, an intermediate frame)
                                         -> imu_link (at vehicle.yaml's imu_x_m, imu_y_m, mounted
                                         yaw -90 deg, roll 90 deg) and base_link -> gps (at
                                         --antenna X,Y; default 1.5,-0.4)
and the IMU's readings and orientation in imu_link's axes instead of the vehicle's.

Usage: write_log_as_bag.py LOG OUT.bag [--twist] [--tf [--antenna X,Y]]
"""
import csv
import math
import sys

import genpy
import rosbag
import yaml
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, NavSatFix
from geometry_msgs.msg import TransformStamped
from std_msgs.msg import Float64
from tf2_msgs.msg import TFMessage

# --tf: the IMU mounted yaw -90 deg, roll 90 deg (tf's static_transform_publisher yaw pitch roll):
# body_R_sensor = Rz(-90) Rx(90), as the quaternion (x, y, z, w).
MOUNTING = (0.5, -0.5, -0.5, 0.5)
CHASSIS_UP_M = 0.3


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def stamp(t):
    nanoseconds = round(float(t) * 1e9)
    return genpy.Time(nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000)


def wheel_angles(log, wheels):
    """Cumulative rear wheel angles (rad) from rad or ticks columns."""
    if "rl_rad" in wheels[0]:
        return [(float(r["rl_rad"]), float(r["rr_rad"])) for r in wheels]
    with open(f"{log}/vehicle.yaml") as f:
        ticks_per_rev = float(yaml.safe_load(f)["ticks_per_rev"])
    scale = 2 * math.pi / ticks_per_rev
    return [(float(r["rl_ticks"]) * scale, float(r["rr_ticks"]) * scale) for r in wheels]


def write_twist(bag, log, wheels):
    with open(f"{log}/vehicle.yaml") as f:
        vehicle = yaml.safe_load(f)
    c_rl, c_rr = vehicle["circumference_rl_m"], vehicle["circumference_rr_m"]
    track = vehicle["track_width_m"]
    angles = wheel_angles(log, wheels)
    for k in range(1, len(wheels)):
        dt = float(wheels[k]["t"]) - float(wheels[k - 1]["t"])
        left = (angles[k][0] - angles[k - 1][0]) / (2 * math.pi) * c_rl / dt
        right = (angles[k][1] - angles[k - 1][1]) / (2 * math.pi) * c_rr / dt
        odom = Odometry()
        odom.header.stamp = stamp(wheels[k]["t"])
        odom.child_frame_id = "base_link"
        odom.twist.twist.linear.x = (left + right) / 2
        odom.twist.twist.angular.z = (right - left) / track
        bag.write("/odom", odom, odom.header.stamp)


def quaternion_product(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def rotate(q, v):
    """q (x, y, z, w) applied to the vector v."""
    x, y, z, _ = quaternion_product(quaternion_product(q, (*v, 0.0)), (-q[0], -q[1], -q[2], q[3]))
    return (x, y, z)


def inverse(q):
    return (-q[0], -q[1], -q[2], q[3])


def transform(parent, child, t, translation, rotation=(0.0, 0.0, 0.0, 1.0)):
    message = TransformStamped()
    message.header.stamp = t
    message.header.frame_id = parent
    message.child_frame_id = child
    (message.transform.translation.x, message.transform.translation.y,
     message.transform.translation.z) = translation
    (message.transform.rotation.x, message.transform.rotation.y,
     message.transform.rotation.z, message.transform.rotation.w) = rotation
    return message


def write_static_transforms(bag, log, first_t, antenna):
    with open(f"{log}/vehicle.yaml") as f:
        vehicle = yaml.safe_load(f)
    imu_place = (vehicle.get("imu_x_m", 0.0), vehicle.get("imu_y_m", 0.0), -CHASSIS_UP_M)
    t = stamp(first_t)
    message = TFMessage()
    message.transforms = [
        transform("base_link", "chassis", t, (0.0, 0.0, CHASSIS_UP_M)),
        transform("chassis", "imu_link", t, imu_place, MOUNTING),
        transform("/base_link", "gps", t, (antenna[0], antenna[1], 1.4)),
    ]
    bag.write("/tf_static", message, t)


def main():
    log, out = sys.argv[1], sys.argv[2]
    twist = "--twist" in sys.argv[3:]
    tf = "--tf" in sys.argv[3:]
    antenna = (1.5, -0.4)
    if "--antenna" in sys.argv[3:]:
        antenna = tuple(float(v) for v in sys.argv[sys.argv.index("--antenna") + 1].split(","))
    sensor_R_body = inverse(MOUNTING) if tf else (0.0, 0.0, 0.0, 1.0)
    wheels, gnss = rows(f"{log}/wheels.csv"), rows(f"{log}/gnss.csv")
    imu, heading = rows(f"{log}/imu.csv"), rows(f"{log}/heading.csv")
    same_stamps = [r["t"] for r in imu] == [r["t"] for r in heading]
    if not same_stamps and not twist:
        sys.exit("heading.csv must have imu.csv's time stamps")
    with rosbag.Bag(out, "w", compression="lz4") as bag:
        if tf:
            write_static_transforms(bag, log, wheels[0]["t"], antenna)
        if twist:
            write_twist(bag, log, wheels)
        else:
            for r, (rl, rr) in zip(wheels, wheel_angles(log, wheels)):
                joints = JointState()
                joints.header.stamp = stamp(r["t"])
                joints.name = ["front_left_wheel", "rear_left_wheel", "rear_right_wheel"]
                joints.position = [0.0, rl, rr]
                bag.write("/joint_states", joints, joints.header.stamp)
        if "drive_force_n" in wheels[0]:
            for r in wheels:
                bag.write("/drive_force", Float64(float(r["drive_force_n"])), stamp(r["t"]))
        for k, r in enumerate(imu):
            message = Imu()
            message.header.stamp = stamp(r["t"])
            message.header.frame_id = "imu_link"
            if same_stamps:
                # world_R_sensor = world_R_body body_R_sensor
                yaw = float(heading[k]["heading"])
                world_R_body = (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
                (message.orientation.x, message.orientation.y, message.orientation.z,
                 message.orientation.w) = quaternion_product(world_R_body, inverse(sensor_R_body))
            (message.angular_velocity.x, message.angular_velocity.y,
             message.angular_velocity.z) = rotate(sensor_R_body, (0.0, 0.0, float(r["wz"])))
            (message.linear_acceleration.x, message.linear_acceleration.y,
             message.linear_acceleration.z) = rotate(sensor_R_body,
                                                     (float(r["ax"]), float(r["ay"]), 9.81))
            bag.write("/imu/data", message, message.header.stamp)
        for r in gnss:
            fix = NavSatFix()
            fix.header.stamp = stamp(r["t"])
            fix.latitude, fix.longitude = float(r["lat"]), float(r["lon"])
            # NavSatFix's convention for an altitude not known; 0 would state a flat road.
            fix.altitude = float(r["alt"]) if "alt" in r else float("nan")
            variance = float(r.get("sigma_m", 1.0)) ** 2
            fix.position_covariance = [variance, 0, 0, 0, variance, 0, 0, 0, 4 * variance]
            fix.position_covariance_type = NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN
            bag.write("/fix", fix, fix.header.stamp)


if __name__ == "__main__":
    main()
