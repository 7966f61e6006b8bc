#!/usr/bin/python3
"""Seed corpora for the fuzz harnesses, cut from the repository's examples and configs.

Run from the repository root: /usr/bin/python3 fuzz/make_corpus.py. Writes fuzz/corpus/<harness>/.
Regression reproducers live in fuzz/regressions/<harness>/ and are never overwritten.
"""
import pathlib

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
    track = "# x_m,y_m,w_tr_right_m,w_tr_left_m\n" + "".join(
        f"{x},{y},5,5\n" for x, y in [(0, 0), (50, 0), (100, 10), (120, 50), (100, 90), (50, 100), (0, 90), (-20, 50), (-10, 10)])
    write("csv_streams", "track", bytes([5]) + track.encode())


def yaml_configs():
    write("yaml_configs", "config-methods", b"\x00method: batch\nbatch:\n  adapt_gnss_noise: true\n")
    write("yaml_configs", "config-empty", b"\x00{}\n")
    write("yaml_configs", "vehicle", b"\x01" + (EXAMPLE / "vehicle.yaml").read_bytes())
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
    write("import_map", "speeds-and-truth", """vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
streams:
  wheels: {file: wheels.csv, time: {column: time_ms, unit: ms}, rl: {column: speed_kmh, unit: km/h}, rr: {column: speed_kmh, unit: km/h}}
  gnss: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}}
  truth: {file: gnss.csv, time: {column: time_ms, unit: ms}, position: latlon, lat: {column: lat, unit: deg}, lon: {column: lon, unit: deg}, alt: {column: alt, unit: m}, heading: course}
""")


def log_pipeline():
    for lines in (30, 400):
        parts = [head(EXAMPLE / "wheels.csv", lines * 5), head(EXAMPLE / "gnss.csv", lines)]
        write("log_pipeline", f"wheels-gnss-{lines}", "#--\n".join(parts))
        parts.append(head(EXAMPLE / "imu.csv", lines * 5))
        write("log_pipeline", f"with-imu-{lines}", "#--\n".join(parts))


if __name__ == "__main__":
    csv_streams()
    yaml_configs()
    import_map()
    log_pipeline()
