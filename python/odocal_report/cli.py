"""odocal report RESULT.json --log LOG --out report.html (also `python3 -m odocal_report`)."""
import argparse
import json
import os
import sys
import tempfile

from . import figures, page


def main(argv=None):
    parser = argparse.ArgumentParser(prog="odocal report",
                                     description="One calibration as a static HTML page")
    parser.add_argument("result", help="odocal calibrate --json output")
    parser.add_argument("--log", required=True, help="the log it calibrated")
    parser.add_argument("--out", required=True, help="HTML file to write")
    parser.add_argument("--window", type=float, default=60.0, help="held-out window, s")
    args = parser.parse_args(argv)
    import odocal

    try:
        with open(args.result) as f:
            result = json.load(f)
        if "circumference_rl_m" not in result or "method" not in result:
            raise ValueError(f"{args.result}: not an odocal calibrate --json result")
        log = odocal.read_log(args.log)
        findings = odocal.doctor(args.log)
        calibrated = (result["circumference_rl_m"], result["circumference_rr_m"],
                      result.get("track_width_m", log.vehicle.track_width_m))
        nominal = (log.vehicle.circumference_rl_m, log.vehicle.circumference_rr_m,
                   log.vehicle.track_width_m)
        drift = odocal.validate(log, calibrated, window_s=args.window)
        plots = [figures.track_figure(log, nominal, calibrated),
                 *figures.drift_figures(log, drift, args.window),
                 figures.iterations_figure(result)]
        text = page.render(f"odocal calibration: {os.path.basename(os.path.abspath(args.log))}",
                           result, findings, drift, plots)
    except OSError as error:
        print(f"odocal: error: {error.filename}: {error.strerror}", file=sys.stderr)
        return 2
    except (ValueError, odocal.Error) as error:
        print(f"odocal: error: {error}", file=sys.stderr)
        return 2
    # Whole or not at all: a temporary file beside the target, renamed into place.
    directory = os.path.dirname(os.path.abspath(args.out))
    try:
        with tempfile.NamedTemporaryFile("w", dir=directory, delete=False, suffix=".tmp") as f:
            f.write(text)
            temporary = f.name
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        os.replace(temporary, args.out)
    except OSError as error:
        print(f"odocal: error: {args.out}: {error.strerror}", file=sys.stderr)
        return 1
    print(f"report       {args.out}")
    return 0
