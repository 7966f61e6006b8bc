#!/usr/bin/python3
"""Commands that stream a log (issue 21; figures in docs/performance.md, "Long logs"): time and
peak memory of `odocal deadreckon`, `odocal doctor` and `odocal import csv` against the log's
length. Logs: the urban scenario with every sensor at 100 Hz (bench/long_drive_bench.py makes the
same), repeated to 1, 3 and 10 hours, with truth.csv; the import converts the log's own files
through a column map, the truth's heading from its course. Each command runs under
/usr/bin/time; peak = maximum resident set. Run from the repository after `make build`:

    ODOCAL_CLI=build/apps/odocal/odocal /usr/bin/python3 bench/streaming_bench.py \\
        --work /tmp/streaming [--hours 1 3 10]
"""
import argparse
import os
import shutil
import subprocess

import long_drive_bench as drives

MAP = """vehicle: {{track_width_m: 1.6, circumference_rl_m: {c}, circumference_rr_m: {c},
          ticks_per_rev: 96, counter_bits: 16}}
streams:
  wheels: {{file: wheels.csv, time: {{column: t, unit: s}},
           rl: {{column: rl_ticks, unit: ticks}}, rr: {{column: rr_ticks, unit: ticks}}}}
  gnss: {{file: gnss.csv, time: {{column: t, unit: s}}, position: local,
         x: {{column: x, unit: m}}, y: {{column: y, unit: m}}, sigma: {{column: sigma_m, unit: m}}}}
  imu: {{file: imu.csv, time: {{column: t, unit: s}}, ax: {{column: ax, unit: m/s^2}},
        ay: {{column: ay, unit: m/s^2}}, wz: {{column: wz, unit: rad/s}}}}
  heading: {{file: heading.csv, time: {{column: t, unit: s}}, heading: {{column: heading, unit: rad}}}}
  truth: {{file: truth.csv, time: {{column: t, unit: s}}, position: local,
          x: {{column: x, unit: m}}, y: {{column: y, unit: m}}}}
"""


def log_mib(log):
    """Every stream file's values at 8 bytes, truth included (what a whole-log reader holds)."""
    values = 0
    for name in ("wheels.csv", "gnss.csv", "imu.csv", "heading.csv", "truth.csv"):
        rows, columns = drives.rows_and_columns(os.path.join(log, name))
        values += rows * columns
    return 8.0 * values / (1024.0 * 1024.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work", required=True)
    parser.add_argument("--hours", type=float, nargs="*", default=[1.0, 3.0, 10.0])
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print("| log | wheel samples | log values | deadreckon: time | peak | doctor: time | peak | "
          "import csv: time | peak |")
    print("|---|---|---|---|---|---|---|---|---|")
    for hours in args.hours:
        scenario, laps = drives.urban_scenario(args.work, hours)
        log = os.path.join(args.work, f"urban-100hz-{laps}")
        drives.simulate(log, "--scenario", scenario, "--laps", str(laps))
        circumference = [line.split(":")[1].strip() for line in open(os.path.join(log, "vehicle.yaml"))
                         if line.startswith("circumference_rl_m")][0]
        map_file = os.path.join(args.work, "map.yaml")
        open(map_file, "w").write(MAP.format(c=circumference))
        imported = os.path.join(args.work, "imported")
        shutil.rmtree(imported, ignore_errors=True)
        dr_s, dr_mb = drives.measured("deadreckon", log, "--out", os.path.join(args.work, "dr.csv"))
        doctor = subprocess.run(["/usr/bin/time", "-f", "%e %M", drives.CLI, "doctor", log],
                                capture_output=True, text=True)
        doctor_s, doctor_kb = doctor.stderr.strip().splitlines()[-1].split()
        import_s, import_mb = drives.measured("import", "csv", "--map", map_file, "--in", log,
                                              "--out", imported)
        samples = drives.rows_and_columns(os.path.join(log, "wheels.csv"))[0]
        print(f"| urban, 100 Hz, {hours:g} h ({laps} laps) | {samples} | {log_mib(log):.0f} MiB | "
              f"{dr_s:.2f} s | {dr_mb:.0f} MiB | {float(doctor_s):.2f} s | "
              f"{float(doctor_kb) / 1024.0:.0f} MiB | {import_s:.2f} s | {import_mb:.0f} MiB |",
              flush=True)


if __name__ == "__main__":
    main()
