"""The odocal-fleet command line (docs/fleet.md)."""
import argparse
import sys

from . import run


def main(argv=None):
    parser = argparse.ArgumentParser(prog="odocal-fleet",
                                     description="Calibrate a fleet's drives and keep the results")
    commands = parser.add_subparsers(dest="command", required=True)
    run_parser = commands.add_parser("run", help="calibrate every drive not yet in the database")
    run_parser.add_argument("logs", nargs="+", help="log directories, or directories holding "
                            "VEHICLE/DRIVE/ log directories")
    run_parser.add_argument("--db", required=True, help="SQLite database (created if missing)")
    where = run_parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="a running Dask scheduler, e.g. tcp://HOST:8786")
    where.add_argument("--workers", type=int, default=2,
                       help="worker processes of the local Dask cluster (0: serial, no Dask)")
    run_parser.add_argument("--method", default="batch",
                            help="iterative, fixed-p, augmented or batch (default batch)")
    run_parser.add_argument("--config", help="calibration options YAML (odocal calibrate --config)")
    run_parser.add_argument("--retry-failed", action="store_true",
                            help="try the drives that failed before again")
    args = parser.parse_args(argv)
    if args.command == "run":
        if args.workers < 0:
            parser.error("--workers must be 0 or more")
        return run.run(args)
    return 2


if __name__ == "__main__":
    sys.exit(main())
