"""Speed at scale (issue 26): `midsurf run` on the corpus and on generated families, against the I/O floor.

Usage: .venv/bin/python scripts/bench_scale.py [--corpus DIR] [--holes 100,400,...] [--ribs 10,20,...]
                                               [--skip-corpus] [--skip-family] [--midsurf BIN] [--keep DIR]
                                               (run by scripts/bench)

Per part: wall time, CPU time (user + system, the sidecar's included: steadier than wall time on a shared
machine) and peak memory of `midsurf run` (/usr/bin/time), its load and stitch stages
(from the report), the I/O floor (import OCP + read the input STEP + write a STEP of the output's size, in a
fresh Python: ../shared/eval/io_floor.py when present, else the same steps here) and time / floor. Then the
corpus median and worst ratios, and per family the scaling exponent b of time ~ a * faces^b, fitted by least
squares in log-log (total time, and the load stage alone).

Families, built with build123d and cached in target/bench/: perforated plates (1.5 mm sheet, holes of 3 mm
on a 6 mm grid, kept: wider than the sheet is thick) with n x n holes, and ribbed plates (2 mm plate, K ribs
2 mm thick and 10 mm tall on an 8 mm pitch). Timings on a shared machine are noisy: compare runs on an idle one.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
CACHE = REPO / "target/bench"
SHARED_FLOOR = REPO.parent / "shared/eval/io_floor.py"

# The floor's steps, as ../shared/eval/io_floor.py takes them, for checkouts without it.
FLOOR = r"""
import sys, time, tempfile, os
t0 = time.perf_counter()
from OCP.STEPControl import STEPControl_Reader, STEPControl_Writer, STEPControl_AsIs
from OCP.IFSelect import IFSelect_RetDone
t1 = time.perf_counter()
def read(p):
    r = STEPControl_Reader(); assert r.ReadFile(p) == IFSelect_RetDone; r.TransferRoots(); return r.OneShape()
read(sys.argv[1]); t2 = time.perf_counter()
out = read(sys.argv[2]); t3 = time.perf_counter()
w = STEPControl_Writer(); w.Transfer(out, STEPControl_AsIs)
fd, tmp = tempfile.mkstemp(suffix=".step"); os.close(fd); w.Write(tmp); os.unlink(tmp); t4 = time.perf_counter()
print(f"{t1-t0:.2f} {t2-t1:.2f} {t4-t3:.2f} {t1-t0+t2-t1+t4-t3:.2f}")
"""


def perforated(n: int) -> Path:
    """A square sheet with n x n through holes: one face with n^2 inner wires, extruded."""
    path = CACHE / f"perforated_{n * n}.step"
    if not path.is_file():
        from build123d import Face, Location, Plane, Wire, export_step, extrude

        pitch, d, t = 6.0, 3.0, 1.5
        side = (n + 1) * pitch
        holes = [
            Wire.make_circle(d / 2, Plane.XY.move(Location((-side / 2 + pitch * (i + 1), -side / 2 + pitch * (j + 1), 0))))
            for i in range(n)
            for j in range(n)
        ]
        solid = extrude(Face(Wire.make_rect(side, side), holes), t)
        expected = (side * side - n * n * math.pi * d * d / 4) * t
        assert solid.is_valid and abs(solid.volume - expected) < 1e-6 * expected, "holes cut the sheet"
        export_step(solid, str(path))
    return path


def ribbed(k: int) -> Path:
    """A plate with k parallel ribs standing on it (T-joints along every rib)."""
    path = CACHE / f"ribbed_{k}.step"
    if not path.is_file():
        from build123d import Align, Box, BuildPart, Locations, export_step

        pitch, length = 8.0, 60.0
        width = (k + 1) * pitch
        with BuildPart() as part:
            Box(width, length, 2.0, align=(Align.CENTER, Align.CENTER, Align.MAX))
            with Locations(*[(-width / 2 + pitch * (i + 1), 0, 0) for i in range(k)]):
                Box(2.0, length - 10.0, 10.0, align=(Align.CENTER, Align.CENTER, Align.MIN))
        assert part.part.is_valid
        export_step(part.part, str(path))
    return path


def floor(step_in: Path, step_out: Path) -> float | None:
    script = ["-c", FLOOR] if not SHARED_FLOOR.is_file() else [str(SHARED_FLOOR)]
    done = subprocess.run([sys.executable, *script, str(step_in), str(step_out)], capture_output=True, text=True)
    lines = done.stdout.strip().splitlines()
    return float(lines[-1].split()[3]) if done.returncode == 0 and lines else None


def run(midsurf: str, step: Path, work: Path) -> dict:
    out, report, timing = work / f"{step.stem}.step", work / f"{step.stem}.json", work / f"{step.stem}.time"
    cmd = ["/usr/bin/time", "-f", "%e %U %S %M", "-o", str(timing), midsurf, "run", str(step), "-o", str(out),
           "--report", str(report)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall, user, system, rss_kb = timing.read_text().strip().splitlines()[-1].split()
    row = {"part": step.stem, "exit": done.returncode, "time_s": float(wall), "cpu_s": float(user) + float(system),
           "rss_mb": int(rss_kb) / 1024}
    if report.is_file():
        r = json.loads(report.read_text())
        row["faces"] = sum(s["faces"] for s in r["solids"])
        row["load_s"] = r["timings_s"]["load"]
        row["stitch_s"] = r["timings_s"]["stitch"]
    row["floor_s"] = floor(step, out if out.is_file() else step)
    if row["floor_s"]:
        row["ratio"] = row["time_s"] / row["floor_s"]
    return row


def show(row: dict) -> None:
    def f(key: str, fmt: str) -> str:
        width = "".join(c for c in fmt.split(".")[0] if c.isdigit())
        return format(row[key], fmt) if row.get(key) is not None else format("-", f">{width}")

    print(f"{row['part']:<44} {f('faces', '>6')} {row['exit']:>4} {f('time_s', '>8.2f')} {f('cpu_s', '>7.2f')} "
          f"{f('floor_s', '>7.2f')} "
          f"{f('ratio', '>6.1f')} {f('rss_mb', '>8.0f')} {f('load_s', '>7.2f')} {f('stitch_s', '>8.2f')}", flush=True)


def exponent(rows: list[dict], key: str) -> float | None:
    """b of key ~ a * faces^b, least squares in log-log."""
    pts = [(math.log(r["faces"]), math.log(r[key])) for r in rows if r.get("faces") and r.get(key, 0) > 0]
    if len(pts) < 2:
        return None
    mx, my = statistics.fmean(p[0] for p in pts), statistics.fmean(p[1] for p in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--corpus", type=Path, default=REPO.parent / "shared/parts")
    parser.add_argument("--holes", default="100,400,900,1600,2500,5041", help="perforated plates: hole counts (squares)")
    parser.add_argument("--ribs", default="10,20,40,80", help="ribbed plates: rib counts")
    parser.add_argument("--skip-corpus", action="store_true")
    parser.add_argument("--skip-family", action="store_true")
    parser.add_argument("--midsurf", default=str(REPO / "target/release/midsurf"))
    parser.add_argument("--keep", type=Path, help="write the outputs and reports here (e.g. for the judge's --dirs)")
    args = parser.parse_args()
    CACHE.mkdir(parents=True, exist_ok=True)
    if args.keep:
        args.keep.mkdir(parents=True, exist_ok=True)
    work = args.keep or Path(tempfile.mkdtemp(prefix="midsurf-bench-"))
    header = f"{'part':<44} {'faces':>6} {'exit':>4} {'time_s':>8} {'cpu_s':>7} {'floor_s':>7} {'ratio':>6} {'rss_MB':>8} " \
             f"{'load_s':>7} {'stitch_s':>8}"
    if not args.skip_corpus and args.corpus.is_dir():
        print(f"corpus {args.corpus}\n{header}", flush=True)
        rows = []
        for step in sorted(args.corpus.glob("*.step")):
            rows.append(run(args.midsurf, step, work))
            show(rows[-1])
        ratios = sorted(r["ratio"] for r in rows if r.get("ratio") and r["exit"] in (0, 1))
        if ratios:
            print(f"corpus: {len(rows)} parts, time/floor median {statistics.median(ratios):.2f}, worst {ratios[-1]:.2f} "
                  f"(parts that finished); total {sum(r['time_s'] for r in rows):.1f} s", flush=True)
    if not args.skip_family:
        families = {
            "perforated": [perforated(round(math.sqrt(int(h)))) for h in args.holes.split(",") if h],
            "ribbed": [ribbed(int(k)) for k in args.ribs.split(",") if k],
        }
        for name, parts in families.items():
            print(f"\nfamily {name}\n{header}", flush=True)
            rows = []
            for step in parts:
                rows.append(run(args.midsurf, step, work))
                show(rows[-1])
            b, bc, bl = exponent(rows, "time_s"), exponent(rows, "cpu_s"), exponent(rows, "load_s")
            fmt = lambda v: f"{v:.2f}" if v is not None else "-"
            print(f"{name}: scaling exponent in faces: time {fmt(b)}, cpu {fmt(bc)}, load {fmt(bl)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
