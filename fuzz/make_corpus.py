#!/usr/bin/python3
"""Seed corpora for the fuzz harnesses, cut from the repository's examples and configs.

Run from the repository root: /usr/bin/python3 fuzz/make_corpus.py. Writes fuzz/corpus/<harness>/.
Regression reproducers live in fuzz/regressions/<harness>/ and are never overwritten.
"""
import pathlib
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
EXAMPLE = ROOT / "examples" / "figure-eight"


def head(path, lines):
    return "".join(path.read_text().splitlines(keepends=True)[:lines])


def write(harness, name, data):
    directory = CORPUS / harness
    directory.mkdir(parents=True, exist_ok=True)
    (directory / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def csv_streams():
    for selector, stream in enumerate(["wheels", "gnss", "imu", "heading", "truth"]):
        for lines in (3, 40):
            write("csv_streams", f"{stream}-{lines}", bytes([selector]) + head(EXAMPLE / f"{stream}.csv", lines).encode())
    rows = head(EXAMPLE / "wheels.csv", 40).splitlines()
    with_force = [rows[0] + ",drive_force_n"] + [f"{row},{(k % 7 - 3) * 400.0}" for k, row in enumerate(rows[1:])]
    write("csv_streams", "wheels-drive-force", bytes([0]) + ("\n".join(with_force) + "\n").encode())
    track = "# x_m,y_m,w_tr_right_m,w_tr_left_m\n" + "".join(
        f"{x},{y},5,5\n" for x, y in [(0, 0), (50, 0), (100, 10), (120, 50), (100, 90), (50, 100), (0, 90), (-20, 50), (-10, 10)])
    write("csv_streams", "track", bytes([5]) + track.encode())


def yaml_configs():
    write("yaml_configs", "config-methods", b"\x00method: batch\nbatch:\n  adapt_gnss_noise: true\n")
    write("yaml_configs", "config-empty", b"\x00{}\n")
    write("yaml_configs", "vehicle", b"\x01" + (EXAMPLE / "vehicle.yaml").read_bytes())
    write("yaml_configs", "vehicle-physical-tyre",
          b"\x01track_width_m: 1.6\ncircumference_rl_m: 1.96\ncircumference_rr_m: 1.96\n"
          b"wheelbase_m: 2.7\ntyre_model: {k_load_s2pm: 0.002, k_drive_slip: 0.05, "
          b"k_brake_slip: 0.018, k_side_slip_s2pm: -0.005}\nbody: {rear_axle_load_share: 0.45, cg_height_m: 0.55, "
          b"rear_roll_share: 0.45, mass_kg: 1500, drag_area_m2: 0.7, rolling_resistance: 0.012}\n")
    for scenario in sorted((ROOT / "config" / "scenarios").glob("*.yaml")):
        write("yaml_configs", f"scenario-{scenario.stem}", b"\x02" + scenario.read_bytes())


def import_map():
    write("import_map", "ticks-and-latlon", """vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96, ticks_per_rev: 96, counter_bits: 16}
streams:
  wheels: {file: wheels.csv, time: {column: time_ms, unit: ms}, rl: {column: left, unit: ticks}, rr: {column: right, unit: ticks}}
  gnss: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}, alt: {column: alt, unit: m}}
  imu: {file: imu.csv, time: {column: time_ms, unit: ms}, frame: frd, ax: {column: ax, unit: m/s^2}, ay: {column: ay, unit: m/s^2}, wz: {column: gz, unit: rad/s}}
  heading: {file: gnss.csv, time: {column: time_ms, unit: ms}, convention: compass_cw, heading: {column: hdg_deg, unit: deg}}
""")
    write("import_map", "drive-force", """vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96, ticks_per_rev: 96, counter_bits: 16, body: {mass_kg: 1500}}
streams:
  wheels: {file: wheels.csv, time: {column: time_ms, unit: ms}, rl: {column: left, unit: ticks}, rr: {column: right, unit: ticks}, drive_force: {file: imu.csv, time: {column: time_ms, unit: ms, offset_s: 0.2}, column: ax, unit: kN}}
  gnss: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}}
""")
    write("import_map", "speeds-and-truth", """vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
streams:
  wheels: {file: wheels.csv, time: {column: time_ms, unit: ms}, rl: {column: speed_kmh, unit: km/h}, rr: {column: speed_kmh, unit: km/h}}
  gnss: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}}
  truth: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}, alt: {column: alt, unit: m}, heading: course}
""")


def every(path, step):
    """The header and every step-th row of a CSV file, as text."""
    lines = path.read_text().splitlines(keepends=True)
    return lines[0] + "".join(lines[1::step])


def log_pipeline():
    for lines in (30, 400):
        parts = [head(EXAMPLE / "wheels.csv", lines * 5), head(EXAMPLE / "gnss.csv", lines)]
        write("log_pipeline", f"wheels-gnss-{lines}", "#--\n".join(parts))
        parts.append(head(EXAMPLE / "imu.csv", lines * 5))
        write("log_pipeline", f"with-imu-{lines}", "#--\n".join(parts))
    # The whole example at a fifth of its rates: under 8 KB, and still a log that calibrates,
    # so that a fuzzer with a small -max_len reaches every layer.
    parts = [every(EXAMPLE / "wheels.csv", 10), every(EXAMPLE / "gnss.csv", 5)]
    write("log_pipeline", "compact-calibrates", "#--\n".join(parts))
    # The harness judges the model on inputs of even length: this one is, by a final newline.
    judged = "#--\n".join(parts)
    write("log_pipeline", "compact-judged", judged + "\n" * (len(judged.encode()) % 2))
    parts.append(every(EXAMPLE / "imu.csv", 25))
    write("log_pipeline", "compact-with-imu", "#--\n".join(parts))


def ros1_bag():
    """ROS 1 bags written by ROS's own rosbag (Debian's python3-rosbag), each compression."""
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as out:
        subprocess.run(["/usr/bin/python3", str(ROOT / "tests" / "bag" / "write_ros1_bags.py"), out,
                        "--count", "6"], check=True)
        for compression in ("none", "bz2", "lz4"):
            write("ros1_bag", f"written-{compression}", (pathlib.Path(out) / f"written_{compression}.bag").read_bytes())


def cdr_string(text):
    data = text.encode() + b"\0"
    return b"\0\1\0\0" + struct.pack("<I", len(data)) + data


def cdr_imu(k):
    """sensor_msgs/msg/Imu in CDR: stamp, frame id, then 8-byte aligned doubles."""
    body = struct.pack("<iI", 100 + k, 0) + struct.pack("<I", 4) + b"imu\0"
    body += b"\0" * ((8 - len(body) % 8) % 8)
    body += struct.pack("<4d", 0, 0, 0, 1) + struct.pack("<9d", *[0] * 9)
    body += struct.pack("<3d", 0, 0, 0.1 * k) + struct.pack("<9d", *[0] * 9)
    body += struct.pack("<3d", 1.0, 0, 9.8) + struct.pack("<9d", *[0] * 9)
    return b"\0\1\0\0" + body


IMU_ROS2MSG = """std_msgs/Header header
geometry_msgs/Quaternion orientation
float64[9] orientation_covariance
geometry_msgs/Vector3 angular_velocity
float64[9] angular_velocity_covariance
geometry_msgs/Vector3 linear_acceleration
float64[9] linear_acceleration_covariance
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
"""


def mcap_record(opcode, content):
    return bytes([opcode]) + struct.pack("<Q", len(content)) + content


def mcap_string(text):
    data = text.encode() if isinstance(text, str) else text
    return struct.pack("<I", len(data)) + data


def mcap_file(compression, chunked):
    """An MCAP file as the specification describes it (https://mcap.dev/spec)."""
    import zlib
    magic = b"\x89MCAP0\r\n"
    records = mcap_record(0x03, struct.pack("<H", 1) + mcap_string("sensor_msgs/msg/Imu") + mcap_string("ros2msg") + mcap_string(IMU_ROS2MSG))
    records += mcap_record(0x04, struct.pack("<HH", 1, 1) + mcap_string("/imu/data") + mcap_string("cdr") + struct.pack("<I", 0))
    records += mcap_record(0x03, struct.pack("<H", 2) + mcap_string("std_msgs/msg/String") + mcap_string("ros2msg") + mcap_string("string data"))
    records += mcap_record(0x04, struct.pack("<HH", 2, 2) + mcap_string("/topic") + mcap_string("cdr") + struct.pack("<I", 0))
    for k in range(4):
        for channel, data in ((1, cdr_imu(k)), (2, cdr_string(f"hello {k}"))):
            records += mcap_record(0x05, struct.pack("<HIQQ", channel, k, 1000 + k, 1000 + k) + data)
    out = magic + mcap_record(0x01, mcap_string("ros2") + mcap_string("odocal corpus"))
    if chunked:
        if compression == "lz4":
            import lz4.frame
            packed = lz4.frame.compress(records)
        elif compression == "zstd":
            import subprocess
            packed = subprocess.run(["zstd", "-q", "-c"], input=records, check=True, capture_output=True).stdout
        else:
            packed = records
        out += mcap_record(0x06, struct.pack("<QQQI", 1000, 1003, len(records), zlib.crc32(records)) + mcap_string(compression) + struct.pack("<Q", len(packed)) + packed)
    else:
        out += records
    out += mcap_record(0x0F, struct.pack("<I", 0)) + mcap_record(0x02, struct.pack("<QQI", 0, 0, 0)) + magic
    return out


def mcap():
    write("mcap", "unchunked", mcap_file("", False))
    for compression in ("", "lz4", "zstd"):
        write("mcap", f"chunk-{compression or 'stored'}", mcap_file(compression, True))


def sqlite3_bag():
    """A rosbag2 SQLite3 file with the Iron schema (topics, messages, message_definitions)."""
    import sqlite3
    import tempfile
    with tempfile.TemporaryDirectory() as out:
        path = pathlib.Path(out) / "bag.db3"
        db = sqlite3.connect(path)
        db.executescript("""
            CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
            CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL,
                type_description_hash TEXT NOT NULL);
            CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL,
                encoding TEXT NOT NULL, encoded_message_definition TEXT NOT NULL,
                type_description_hash TEXT NOT NULL);
            CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                timestamp INTEGER NOT NULL, data BLOB NOT NULL);""")
        db.execute("INSERT INTO topics VALUES (1, '/imu/data', 'sensor_msgs/msg/Imu', 'cdr', '', '')")
        db.execute("INSERT INTO topics VALUES (2, '/topic', 'std_msgs/msg/String', 'cdr', '', '')")
        db.execute("INSERT INTO message_definitions VALUES (1, 'sensor_msgs/msg/Imu', 'ros2msg', ?, '')", (IMU_ROS2MSG,))
        for k in range(3):
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?, ?)", (1000 + k, cdr_imu(k)))
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (2, ?, ?)", (1000 + k, cdr_string(f"hi {k}")))
        db.commit()
        db.close()
        write("sqlite3_bag", "iron-schema", path.read_bytes())


def message_decoder():
    write("message_decoder", "imu-cdr-known", bytes([3, 0]) + cdr_imu(2))
    write("message_decoder", "string-cdr-definition", bytes([1, 0]) + b"string data\0" + cdr_string("hello"))
    write("message_decoder", "imu-cdr-definition", bytes([1, 0]) + IMU_ROS2MSG.encode() + b"\0" + cdr_imu(1))
    joint = struct.pack("<IIII", 7, 5, 0, 0) + struct.pack("<I", 2) + struct.pack("<I", 2) + b"rl" + struct.pack("<I", 2) + b"rr"
    joint += struct.pack("<I", 2) + struct.pack("<2d", 1.5, 2.5) + struct.pack("<I", 0) + struct.pack("<I", 0)
    write("message_decoder", "jointstate-ros1-known", bytes([2, 2]) + joint)
    write("message_decoder", "arrays-ros1-definition", bytes([0, 0]) + b"uint8[<=3] a\nstring[2] s\nint32[] v\nMSG_BAD\0" + bytes(16))


if __name__ == "__main__":
    csv_streams()
    yaml_configs()
    import_map()
    log_pipeline()
    ros1_bag()
    mcap()
    sqlite3_bag()
    message_decoder()
