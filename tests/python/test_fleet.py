"""odocal-fleet run on a small simulated fleet: every drive calibrated once, results identical
to a serial run, a broken drive recorded without stopping the run, re-runs skipping what is
done, --retry-failed, and a run resumed after a partial one counting nothing twice."""
import os
import shutil
import sqlite3
import subprocess
import sys

import pytest

from odocal_fleet import cli

ODOCAL = os.environ["ODOCAL_CLI"]


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    root = tmp_path_factory.mktemp("fleet")
    for vehicle, wear in (("car-a", 1.0), ("car-b", 2.0)):
        for drive, seed in (("drive-1", 1), ("drive-2", 2)):
            out = root / vehicle / drive
            subprocess.run([ODOCAL, "simulate", "--ideal", "--laps", "1", "--seed", str(seed),
                            "--wear-rl", str(wear), "--wear-rr", "0.5", "--out", str(out)],
                           check=True, stdout=subprocess.DEVNULL)
    broken = root / "car-b" / "drive-3"
    shutil.copytree(root / "car-b" / "drive-1", broken)
    with open(broken / "gnss.csv", "a") as f:
        f.write("not,a,row\n")
    return root


def rows(db, sql):
    with sqlite3.connect(db) as connection:
        return sorted(connection.execute(sql).fetchall())


CALIBRATIONS = "SELECT d.vehicle_id, d.path, c.circumference_rl_m, c.circumference_rr_m, " \
               "c.termination FROM calibrations c JOIN drives d USING (drive_key)"


def test_run_serial_and_parallel_agree_and_failures_are_kept(fleet, tmp_path):
    serial, parallel = tmp_path / "serial.sqlite", tmp_path / "parallel.sqlite"
    assert cli.main(["run", str(fleet), "--db", str(serial), "--workers", "0",
                     "--method", "iterative"]) == 0
    assert cli.main(["run", str(fleet), "--db", str(parallel), "--workers", "2",
                     "--method", "iterative"]) == 0
    done = rows(serial, CALIBRATIONS)
    assert len(done) == 4 and done == rows(parallel, CALIBRATIONS)
    # The worn left wheels: car-b's 2 mm shows as a smaller circumference than car-a's 1 mm.
    by_vehicle = {}
    for vehicle, _, c_rl, _, termination in done:
        assert termination == "converged"
        by_vehicle.setdefault(vehicle, []).append(c_rl)
    assert max(by_vehicle["car-b"]) < min(by_vehicle["car-a"])
    failures = rows(serial, "SELECT vehicle_id, error, attempts FROM failures")
    assert len(failures) == 1 and failures[0][0] == "car-b" and failures[0][2] == 1
    assert "gnss.csv" in failures[0][1]
    assert rows(serial, "SELECT count(*) FROM findings") == rows(parallel, "SELECT count(*) FROM findings")


def test_reruns_skip_what_is_done_and_retry_failed(fleet, tmp_path, capsys):
    db = tmp_path / "fleet.sqlite"
    # A partial run (one vehicle), then the whole fleet: nothing done twice.
    assert cli.main(["run", str(fleet / "car-a"), "--db", str(db), "--workers", "0",
                     "--method", "iterative"]) == 0
    assert cli.main(["run", str(fleet), "--db", str(db), "--workers", "0",
                     "--method", "iterative"]) == 0
    assert "5 drives, 2 already in" in capsys.readouterr().out
    assert rows(db, "SELECT count(*) FROM drives") == [(4,)]
    assert cli.main(["run", str(fleet), "--db", str(db), "--workers", "0",
                     "--method", "iterative"]) == 0
    assert "0 to do" in capsys.readouterr().out
    assert cli.main(["run", str(fleet), "--db", str(db), "--workers", "0", "--method",
                     "iterative", "--retry-failed"]) == 0
    assert rows(db, "SELECT attempts FROM failures") == [(2,)]
    # Another method is another calibration of the same drives.
    assert cli.main(["run", str(fleet / "car-a"), "--db", str(db), "--workers", "0",
                     "--method", "batch"]) == 0
    assert rows(db, "SELECT count(*) FROM drives") == [(6,)]


def test_the_command_runs_as_a_module(fleet, tmp_path):
    db = tmp_path / "fleet.sqlite"
    run = subprocess.run([sys.executable, "-m", "odocal_fleet", "run", str(fleet / "car-a"),
                          "--db", str(db), "--workers", "0", "--method", "iterative"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "2 calibrated, 0 failed" in run.stdout


def test_a_worker_calibrates_on_one_thread_unless_the_options_say_with_the_same_result(fleet):
    from odocal_fleet import tasks
    drive = str(fleet / "car-a" / "drive-1")
    given = {"batch": {"tyre_model": "none"}}
    one = tasks.calibrate_drive(drive, "batch", given, threads=1)["result"]
    own = tasks.calibrate_drive(drive, "batch", given)["result"]
    stated = tasks.calibrate_drive(drive, "batch", {"batch": {"threads": 3}}, threads=1)["result"]
    assert one["configuration"]["batch"]["threads"] == 1
    assert one["configuration"]["batch"]["tyre_model"] == "none"  # the rest of the options kept
    assert own["configuration"]["batch"]["threads"] == 0
    assert stated["configuration"]["batch"]["threads"] == 3
    assert given == {"batch": {"tyre_model": "none"}}  # the caller's options left as they were
    for key in ("circumference_rl_m", "circumference_rr_m", "covariance_m2"):
        assert one[key] == own[key]


def test_a_local_clusters_workers_start_with_huge_pages_asked_for():
    from distributed import Client

    from odocal_fleet.run import local_cluster, tunables_with_huge_pages

    assert tunables_with_huge_pages("") == "glibc.malloc.hugetlb=1"
    assert tunables_with_huge_pages("glibc.malloc.check=3") == \
        "glibc.malloc.check=3:glibc.malloc.hugetlb=1"
    assert tunables_with_huge_pages("glibc.malloc.hugetlb=0") is None

    def environment_at_start():  # as the process was started, not as it is now
        with open("/proc/self/environ", "rb") as f:
            variables = f.read().split(b"\0")
        return [v.decode() for v in variables if v.startswith(b"GLIBC_TUNABLES=")]

    cluster = local_cluster(1)
    try:
        with Client(cluster) as client:
            (at_start,) = client.run(environment_at_start).values()
    finally:
        cluster.close()
    assert at_start and "glibc.malloc.hugetlb=1" in at_start[0]
