"""The odocal-fleet command line (docs/fleet.md)."""
import argparse
import sys

from . import health_command, report, run, simulate


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

    health_parser = commands.add_parser("health", help="tyre health per vehicle and rear wheel")
    health_parser.add_argument("--db", required=True, help="the database odocal-fleet run wrote")
    health_parser.add_argument("--json", help="write everything (series, bands, events) here")
    health_parser.add_argument("--method", default="batch", help="whose calibrations (default batch)")
    health_parser.add_argument("--false-alarm-rate", type=float, default=0.01,
                               help="chance of a false event per vehicle over 50 drives (default 0.01)")

    report_parser = commands.add_parser("report", help="the fleet as static HTML pages")
    report_parser.add_argument("--db", required=True, help="the database odocal-fleet run wrote")
    report_parser.add_argument("--out", required=True, help="directory for index.html and a page per vehicle")
    report_parser.add_argument("--method", default="batch", help="whose calibrations (default batch)")
    report_parser.add_argument("--false-alarm-rate", type=float, default=0.01,
                               help="as for health (default 0.01)")

    sim_parser = commands.add_parser("simulate", help="a simulated fleet with known tyre events")
    sim_parser.add_argument("--vehicles", type=int, required=True)
    sim_parser.add_argument("--drives", type=int, required=True, help="drives per vehicle")
    sim_parser.add_argument("--out", required=True, help="directory for VEHICLE/DRIVE/ logs")
    sim_parser.add_argument("--scenario", default="urban",
                            help="built-in scenario or scenario YAML (default urban)")
    sim_parser.add_argument("--laps", type=int, default=3, help="laps per drive (default 3)")
    sim_parser.add_argument("--ideal", action="store_true", help="the paper's ideal vehicle")
    sim_parser.add_argument("--seed", type=int, default=1)
    sim_parser.add_argument("--event-share", type=float, default=0.5,
                            help="share of vehicles with one event (default 0.5)")
    sim_parser.add_argument("--step-mm", type=float, default=1.0,
                            help="radius a tyre change adds, mm (default 1)")
    sim_parser.add_argument("--pressure", type=float, default=0.75,
                            help="inflation after a pressure loss, relative (default 0.75)")
    sim_parser.add_argument("--gap-km", type=float, default=5.0,
                            help="most driving not logged between two drives, km (default 5)")
    sim_parser.add_argument("--doppler-sigma", type=float, default=0.05,
                            help="noise of the receiver's Doppler speed column, m/s (default 0.05)")
    sim_parser.add_argument("--no-doppler", action="store_true",
                            help="drives without a Doppler speed column")
    sim_parser.add_argument("--workers", type=int, default=2, help="simulations in parallel")
    args = parser.parse_args(argv)
    if args.command == "run":
        if args.workers < 0:
            parser.error("--workers must be 0 or more")
        return run.run(args)
    if args.command in ("health", "report"):
        if not 0 < args.false_alarm_rate < 1:
            parser.error("--false-alarm-rate must be between 0 and 1")
        return health_command.run(args) if args.command == "health" else report.run(args)
    if args.command == "simulate":
        if args.vehicles < 1 or args.drives < 1 or args.laps < 1 or args.workers < 1:
            parser.error("--vehicles, --drives, --laps and --workers must be 1 or more")
        if not 0 <= args.event_share <= 1 or not 0.3 <= args.pressure <= 1.5 or args.gap_km < 0:
            parser.error("--event-share in [0, 1], --pressure in [0.3, 1.5], --gap-km >= 0")
        if not 0 <= args.doppler_sigma <= 10:
            parser.error("--doppler-sigma in [0, 10] m/s")
        return simulate.simulate(args)
    return 2


if __name__ == "__main__":
    sys.exit(main())
