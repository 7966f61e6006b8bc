"""Finding drives and naming them: a drive is an odocal log directory (it has wheels.csv); its
vehicle is the directory above it in a VEHICLE/DRIVE/ layout; its key is a content hash of its
files and of the calibration it gets, so that a drive already done is skipped and a changed one
done again."""
import hashlib
import os
from dataclasses import dataclass

LOG_FILES = ("vehicle.yaml", "wheels.csv", "gnss.csv", "imu.csv", "heading.csv")


@dataclass(frozen=True)
class Drive:
    path: str
    vehicle: str
    key: str


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
    """Drives under `paths`; `calibration` (method and options as text) is part of each key."""
    return [Drive(path, os.path.basename(os.path.dirname(path)) or "unknown",
                  content_key(path, calibration)) for path in find_logs(paths)]
