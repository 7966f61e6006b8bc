"""What a worker does with one drive: the doctor, then the calibration. Bad input is an outcome,
not an exception, so that one broken drive never stops a run."""


def calibrate_drive(path, method, options, threads=None):
    """`threads`: the batch's threads per calibration where the options do not say (Dask runs one
    calibration per worker process, each on its core: 1); the result does not depend on it."""
    import odocal  # imported in the worker process

    if threads is not None:
        options = dict(options or {})
        options["batch"] = {"threads": threads, **(options.get("batch") or {})}
    try:
        log = odocal.read_log(path)
        findings = odocal.doctor(path)
        result = odocal.calibrate(log, method=method, options=options).to_dict()
        wheels = log.wheels.t_s
        return {"result": result, "findings": findings, "start_s": float(wheels[0]),
                "duration_s": float(wheels[-1] - wheels[0])}
    except (odocal.Error, ValueError, RuntimeError, OSError) as error:
        return {"error": f"{type(error).__name__}: {error}"}
