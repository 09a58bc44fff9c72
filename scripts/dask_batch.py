#!/usr/bin/env python3
"""Run a `midsurf batch` over a Dask distributed cluster: one task per part.

    scripts/dask_batch.py SOURCE -o OUT [--scheduler tcp://HOST:8786 | --local N] [-- BATCH OPTIONS...]

SOURCE is what `midsurf batch` takes (a folder of STEP files or a CSV/JSON manifest); OUT must be on a file
system every worker sees, and the midsurf executable (--midsurf, default target/release/midsurf of this
checkout) must run on every worker at the same path. BATCH OPTIONS (e.g. --t-max 3 --keep-holes) go to every
part, as for `midsurf batch`.

Task k of the N parts runs `midsurf batch SOURCE -o OUT --shard k/N`: the k-th part in name order, alone,
through `midsurf run` with its own sidecar. So the listing, per-part options, outputs, logs and resume keys are
midsurf's own, not redone here, and a part already up to date costs its task a hash. When every task is done,
the driver runs `midsurf batch SOURCE -o OUT` once on its own machine: every part is then up to date, so that
pass runs nothing and writes the one summary (batch-summary.csv/.json) and the exit code (worst of the parts);
the per-task summaries are removed. Dask schedules, retries lost workers and spreads the parts; nothing here
is a scheduler.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run_part(midsurf: str, source: str, out: str, k: int, n: int, options: list[str]) -> dict:
    """One part (shard k of n, a single part): its summary row, read back from the shard's summary."""
    cmd = [midsurf, "batch", source, "-o", out, "--shard", f"{k}/{n}", *options]
    done = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True)
    summary = Path(out) / f"batch-summary-{k}-of-{n}.json"
    if not summary.is_file():  # the batch itself failed (bad option, unwritable folder): say why
        raise RuntimeError(f"{' '.join(cmd)}: exit {done.returncode}: {done.stderr.strip()}")
    rows = json.loads(summary.read_text())["parts"]
    summary.unlink()
    summary.with_suffix(".csv").unlink(missing_ok=True)
    return rows[0]


def count_parts(midsurf: str, source: str, out: str, options: list[str]) -> int:
    """How many parts SOURCE holds, as midsurf lists them (--plan: no part runs)."""
    done = subprocess.run([midsurf, "batch", source, "-o", out, "--plan", *options], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(done.stderr.strip() or f"midsurf batch --plan: exit {done.returncode}")
    return len(json.loads(done.stdout))


def main(argv: list[str] | None = None, client=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source")
    parser.add_argument("-o", "--output", required=True)
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a running Dask scheduler")
    where.add_argument("--local", type=int, metavar="N", help="start a LocalCluster of N single-thread workers")
    parser.add_argument("--midsurf", default=str(ROOT / "target/release/midsurf"))
    argv = list(sys.argv[1:] if argv is None else argv)
    # Everything after "--" is midsurf's (argparse would take "--t-max" for one of its own options).
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    args.options = argv[split + 1 :]
    midsurf = str(Path(args.midsurf).resolve())
    source, out = str(Path(args.source).resolve()), str(Path(args.output).resolve())

    n = count_parts(midsurf, source, out, args.options)
    cluster = None
    if client is None:
        from dask.distributed import Client, LocalCluster

        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = LocalCluster(n_workers=args.local or 1, threads_per_worker=1)
            client = Client(cluster)
    try:
        from dask.distributed import as_completed

        started = time.monotonic()
        # pure=False: a task is a run with side effects (files), never to be deduplicated or cached by Dask.
        futures = [
            client.submit(run_part, midsurf, source, out, k, n, args.options, key=f"midsurf-part-{k}-of-{n}", pure=False)
            for k in range(1, n + 1)
        ]
        for i, future in enumerate(as_completed(futures), 1):
            row = future.result()
            print(f"dask_batch: [{i}/{n}] {row['part']} exit {row['exit']} {row['time_s']:.1f} s ({row['status']})",
                  file=sys.stderr)
        print(f"dask_batch: {n} parts in {time.monotonic() - started:.1f} s", file=sys.stderr)
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
    # Every part is up to date now: this pass runs none, and writes the summary and the batch's exit code.
    return subprocess.run([midsurf, "batch", source, "-o", out, *args.options]).returncode


if __name__ == "__main__":
    sys.exit(main())
