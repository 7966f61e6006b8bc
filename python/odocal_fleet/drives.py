"""Finding drives and naming them: a drive is an odocal log directory (it has wheels.csv); its
vehicle is vehicle.yaml's vehicle_id, else the directory above it in a VEHICLE/DRIVE/ layout; its
start time and odometer come from drive.yaml when the log has one; its key is a content hash of
its files and of the calibration it gets, so that a drive already done is skipped and a changed
one done again."""
import datetime
import hashlib
import math
import os
from dataclasses import dataclass

import yaml

LOG_FILES = ("vehicle.yaml", "drive.yaml", "wheels.csv", "gnss.csv", "imu.csv", "heading.csv")


@dataclass(frozen=True)
class Drive:
    path: str
    vehicle: str
    key: str
    start_time: str = None     # ISO 8601 (drive.yaml)
    odometer_km: float = None  # the vehicle's odometer at the start (drive.yaml)


def _yaml(path):
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        try:
            data = yaml.safe_load(f)
        except yaml.YAMLError as error:
            raise ValueError(f"{path}: not YAML: {str(error).splitlines()[0]}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a mapping")
    return data


def drive_metadata(path):
    """(vehicle_id or None, start time, odometer_km) from vehicle.yaml and drive.yaml."""
    vehicle = _yaml(os.path.join(path, "vehicle.yaml")).get("vehicle_id")
    drive = _yaml(os.path.join(path, "drive.yaml"))
    unknown = set(drive) - {"start_time", "odometer_km"}
    if unknown:
        raise ValueError(f"{os.path.join(path, 'drive.yaml')}: '{sorted(unknown)[0]}': unknown key "
                         "(start_time, odometer_km)")
    start = drive.get("start_time")
    if start is not None:
        text = start.isoformat() if isinstance(start, datetime.datetime) else str(start)
        try:
            parsed = datetime.datetime.fromisoformat(text.replace("Z", "+00:00"))
        except ValueError:
            raise ValueError(f"{os.path.join(path, 'drive.yaml')}: 'start_time': expected ISO 8601, "
                             f"got '{text}'") from None
        if parsed.tzinfo is None:
            parsed = parsed.replace(tzinfo=datetime.timezone.utc)
        start = parsed.isoformat()
    odometer = drive.get("odometer_km")
    if odometer is not None:
        if isinstance(odometer, bool) or not isinstance(odometer, (int, float)) \
                or not math.isfinite(odometer) or not 0 <= odometer < 1e8:
            raise ValueError(f"{os.path.join(path, 'drive.yaml')}: 'odometer_km': expected a "
                             f"number from 0 to 1e8, got '{odometer}'")
        odometer = float(odometer)
    return (str(vehicle) if vehicle is not None else None), start, odometer


def find_logs(paths):
    """Every log directory at or below `paths`, sorted."""
    found = set()
    for path in paths:
        if not os.path.isdir(path):
            raise SystemExit(f"odocal-fleet: error: {path}: not a directory")
        for root, dirs, files in os.walk(path):
            dirs.sort()
            if "wheels.csv" in files:
                found.add(os.path.abspath(root))
    return sorted(found)


def content_key(path, calibration):
    digest = hashlib.sha256(calibration.encode())
    for name in LOG_FILES:
        file = os.path.join(path, name)
        if not os.path.exists(file):
            continue
        digest.update(name.encode())
        with open(file, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
    return digest.hexdigest()


def drives(paths, calibration):
    """Drives under `paths`; `calibration` (method and options as text) is part of each key.
    A drive whose metadata does not read is returned with `error` instead of failing the run."""
    found, broken = [], []
    for path in find_logs(paths):
        key = content_key(path, calibration)
        fallback = os.path.basename(os.path.dirname(path)) or "unknown"
        try:
            vehicle, start, odometer = drive_metadata(path)
        except (OSError, ValueError) as error:
            broken.append((Drive(path, fallback, key), str(error)))
            continue
        found.append(Drive(path, vehicle or fallback, key, start, odometer))
    return found, broken
