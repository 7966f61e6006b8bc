"""odocal-fleet run: every drive not yet in the database, calibrated as a task on Dask
distributed (a LocalCluster on this machine by default, or a running scheduler), each result
stored as it arrives."""
import json
import os
import sys

from . import database, drives, tasks


class Progress:
    """A one-line progress bar on a terminal; silent otherwise."""

    def __init__(self, total):
        self.total, self.done, self.failed = total, 0, 0
        self.live = sys.stderr.isatty()

    def step(self, failed):
        self.done += 1
        self.failed += failed
        if self.live:
            width = 30
            filled = width * self.done // max(self.total, 1)
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total}"
                             f" drives, {self.failed} failed")
            sys.stderr.flush()

    def close(self):
        if self.live:
            sys.stderr.write("\n")


def tunables_with_huge_pages(existing):
    """GLIBC_TUNABLES with glibc's allocator asking for transparent huge pages, or None where
    `existing` already says how (as the command line does: apps/odocal/large_buffers.hpp)."""
    if existing and "glibc.malloc.hugetlb" in existing:
        return None
    return f"{existing}:glibc.malloc.hugetlb=1" if existing else "glibc.malloc.hugetlb=1"


def local_cluster(workers):
    """A LocalCluster of single-threaded worker processes whose allocator backs its large buffers
    with huge pages: glibc reads the tunable only when a process starts, so it goes into the
    nanny's environment before the spawn (the 10-hour drive: a quarter of its processor time went
    on faulting its buffers in 4 KiB pages; docs/fleet.md)."""
    import dask
    from distributed import LocalCluster

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", default={}) or {})
    tunables = tunables_with_huge_pages(environ.get("GLIBC_TUNABLES",
                                                    os.environ.get("GLIBC_TUNABLES", "")))
    if tunables:
        environ["GLIBC_TUNABLES"] = tunables
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                            dashboard_address=None)


def pending(db, found, retry_failed):
    done, failed = database.done_keys(db), database.failed_keys(db)
    return [d for d in found if d.key not in done and (retry_failed or d.key not in failed)]


def run(args):
    options = None
    if args.config:
        import yaml
        with open(args.config) as f:
            options = yaml.safe_load(f) or {}
    calibration = json.dumps({"method": args.method, "options": options}, sort_keys=True)
    found, broken = drives.drives(args.logs, calibration)
    db = database.connect(args.db)
    for drive, error in broken:  # metadata that does not read: a failure, the run goes on
        if args.retry_failed or drive.key not in database.failed_keys(db):
            database.store(db, drive, {"error": error})
    todo = pending(db, found, args.retry_failed)
    skipped = len(found) - len(todo)
    print(f"odocal-fleet: {len(found) + len(broken)} drives, {skipped} already in {args.db}, "
          f"{len(todo)} to do" + (f", {len(broken)} with unreadable drive.yaml or vehicle.yaml"
                                  if broken else ""))
    progress = Progress(len(todo))
    failed = 0
    if args.workers == 0 and not args.scheduler:
        for drive in todo:  # serial, in this process
            outcome = tasks.calibrate_drive(drive.path, args.method, options)
            database.store(db, drive, outcome)
            failed += "error" in outcome
            progress.step("error" in outcome)
    else:
        from distributed import Client, as_completed

        cluster = None
        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = local_cluster(args.workers)
            client = Client(cluster)
        try:
            # One calibration per worker process and core: each on one thread.
            futures = {client.submit(tasks.calibrate_drive, d.path, args.method, options, 1,
                                     key=f"odocal-{d.key}", pure=False): d for d in todo}
            for future in as_completed(futures):
                drive = futures[future]
                try:
                    outcome = future.result()
                except Exception as error:  # a worker that died: recorded, the run goes on
                    outcome = {"error": f"worker failed: {type(error).__name__}: {error}"}
                database.store(db, drive, outcome)
                failed += "error" in outcome
                progress.step("error" in outcome)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    progress.close()
    print(f"odocal-fleet: {len(todo) - failed} calibrated, {failed} failed "
          f"(see the failures table; --retry-failed tries them again)")
    return 0
