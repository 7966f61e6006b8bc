"""The fleet database (SQLite, Python's own sqlite3): one transaction per drive, so that a killed
run loses nothing it had finished and counts nothing twice. Schema in docs/fleet.md."""
import json
import sqlite3
import time

SCHEMA = """
CREATE TABLE IF NOT EXISTS vehicles (
    vehicle_id TEXT PRIMARY KEY
);
CREATE TABLE IF NOT EXISTS drives (
    drive_key TEXT PRIMARY KEY,          -- sha256 of the log's files and the calibration asked for
    vehicle_id TEXT NOT NULL REFERENCES vehicles(vehicle_id),
    path TEXT NOT NULL,
    start_s REAL,                        -- first wheel sample, on the log's clock
    start_time TEXT,                     -- ISO 8601 (drive.yaml), else NULL
    odometer_km REAL,                    -- the vehicle's odometer at the start (drive.yaml)
    duration_s REAL,
    distance_m REAL,                     -- odometry distance while moving
    done_at REAL NOT NULL                -- UNIX time the result was stored
);
CREATE TABLE IF NOT EXISTS calibrations (
    drive_key TEXT PRIMARY KEY REFERENCES drives(drive_key),
    method TEXT NOT NULL,
    circumference_rl_m REAL, circumference_rr_m REAL, track_width_m REAL,
    sigma_rl_m REAL, sigma_rr_m REAL, covariance_rl_rr_m2 REAL,
    termination TEXT NOT NULL,
    usable INTEGER NOT NULL,
    message TEXT,
    result_json TEXT NOT NULL            -- everything, as odocal calibrate --json writes it
);
CREATE TABLE IF NOT EXISTS findings (
    drive_key TEXT NOT NULL REFERENCES drives(drive_key),
    check_id TEXT NOT NULL,
    severity TEXT NOT NULL,
    what TEXT, evidence TEXT, cause TEXT, fix TEXT
);
CREATE TABLE IF NOT EXISTS failures (
    drive_key TEXT PRIMARY KEY,
    vehicle_id TEXT NOT NULL,
    path TEXT NOT NULL,
    error TEXT NOT NULL,                 -- odocal's one-line message
    attempts INTEGER NOT NULL,
    last_attempt REAL NOT NULL
);
"""


def connect(path):
    db = sqlite3.connect(path)
    db.executescript(SCHEMA)
    columns = {row[1] for row in db.execute("PRAGMA table_info(drives)")}
    with db:  # databases written before drives had a start time and an odometer
        for column, kind in (("start_time", "TEXT"), ("odometer_km", "REAL")):
            if column not in columns:
                db.execute(f"ALTER TABLE drives ADD COLUMN {column} {kind}")
    return db


def done_keys(db):
    return {row[0] for row in db.execute("SELECT drive_key FROM drives")}


def failed_keys(db):
    return {row[0] for row in db.execute("SELECT drive_key FROM failures")}


def store(db, drive, outcome):
    """One drive's outcome (from tasks.calibrate_drive), in one transaction."""
    with db:
        if "error" in outcome:
            db.execute("""INSERT INTO failures VALUES (?, ?, ?, ?, 1, ?)
                          ON CONFLICT(drive_key) DO UPDATE SET error = excluded.error,
                          attempts = attempts + 1, last_attempt = excluded.last_attempt""",
                       (drive.key, drive.vehicle, drive.path, outcome["error"], time.time()))
            return
        result = outcome["result"]
        db.execute("INSERT OR IGNORE INTO vehicles VALUES (?)", (drive.vehicle,))
        db.execute("INSERT INTO drives (drive_key, vehicle_id, path, start_s, start_time, odometer_km,"
                   " duration_s, distance_m, done_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                   (drive.key, drive.vehicle, drive.path, outcome["start_s"], drive.start_time,
                    drive.odometer_km, outcome["duration_s"], result.get("distance_m"), time.time()))
        covariance = result.get("covariance_m2") or [[None, None], [None, None]]
        db.execute("INSERT INTO calibrations VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                   (drive.key, result["method"], result.get("circumference_rl_m"),
                    result.get("circumference_rr_m"), result.get("track_width_m"),
                    result.get("sigma_circumference_rl_m"), result.get("sigma_circumference_rr_m"),
                    covariance[0][1], result["termination"], int(result["usable"]),
                    result.get("message"), json.dumps(result, sort_keys=True)))
        db.executemany("INSERT INTO findings VALUES (?, ?, ?, ?, ?, ?, ?)",
                       [(drive.key, f["check"], f["severity"], f["what"], f["evidence"], f["cause"],
                         f["fix"]) for f in outcome["findings"]])
        db.execute("DELETE FROM failures WHERE drive_key = ?", (drive.key,))
