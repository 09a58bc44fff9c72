"""Benchmark of small-feature suppression (issue 6): a ribbed plate of about 1,000 faces with 400 fillets and
100 small holes, suppressed by midsurf (recognition on the face graph, logical suppression, full run) and by
OCCT's BRepAlgoAPI_Defeaturing removing the same faces.

Usage: .venv/bin/python scripts/bench_features.py [--ribs N]   (run by scripts/bench)

The part is built once with build123d and cached in target/bench/. Prints both timings, the feature counts
and whether each result is valid.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

from build123d import Align, Axis, Box, Cylinder, Pos, export_step
from OCP.BRepAlgoAPI import BRepAlgoAPI_Defeaturing
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Shape
from OCP.collections import List_TopoDS_Shape as TopTools_ListOfShape
from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as ShapeMap

REPO = Path(__file__).resolve().parent.parent
PITCH = 6.0  # rib spacing along x (mm)
PLATE_T, RIB_T, RIB_H, WIDTH = 2.0, 2.0, 10.0, 60.0
ROOT_R, TOP_R, HOLE_D = 0.8, 0.5, 1.5


def ribbed_plate(ribs: int):
    """A plate with `ribs` ribs across it, each with root fillets and rounded top edges (4 fillets per rib),
    and one small through hole between each pair of neighbouring ribs."""
    length = PITCH * (ribs + 1)
    part = Box(length, WIDTH, PLATE_T, align=None)
    for k in range(ribs):
        x = PITCH * (k + 1) - RIB_T / 2
        part += Pos(x, 0, PLATE_T) * Box(RIB_T, WIDTH, RIB_H, align=None)
    part = part.fillet(ROOT_R, edges_along_y_at(part, PLATE_T, length))
    part = part.fillet(TOP_R, edges_along_y_at(part, PLATE_T + RIB_H, length))
    centred = (Align.CENTER, Align.CENTER, Align.MIN)
    for k in range(ribs):
        part -= Pos(PITCH * (k + 1.5), WIDTH / 2, -1) * Cylinder(HOLE_D / 2, PLATE_T + 2, align=centred)
    return part


def edges_along_y_at(part, z: float, length: float):
    """The straight edges along y at height z strictly inside the plate's length (not its rim)."""
    return [
        e
        for e in part.edges().filter_by(Axis.Y)
        if abs(e.center().Z - z) < 1e-6 and 1e-6 < e.center().X < length - 1e-6
    ]


def read_step(path: Path) -> TopoDS_Shape:
    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    return reader.OneShape()


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ribs", type=int, default=100)
    # The walls are 2 thick; the estimate alone would take the 4 mm air gaps between ribs for walls.
    parser.add_argument("--t-max", default="3")
    args = parser.parse_args(argv)
    bench = REPO / "target" / "bench"
    bench.mkdir(parents=True, exist_ok=True)
    part_path = bench / f"ribbed_plate_{args.ribs}.step"
    if not part_path.exists():
        started = time.perf_counter()
        export_step(ribbed_plate(args.ribs), str(part_path))
        print(f"built {part_path.name} in {time.perf_counter() - started:.1f} s")

    midsurf = REPO / "target" / "release" / "midsurf"
    report_path, out_path = bench / "features_report.json", bench / "features_mid.step"
    started = time.perf_counter()
    command = [str(midsurf), "run", str(part_path), "-o", str(out_path), "--report", str(report_path)]
    run = subprocess.run(command + ["--t-max", args.t_max])
    wall = time.perf_counter() - started
    if run.returncode not in (0, 1):
        print(f"midsurf failed with exit code {run.returncode}", file=sys.stderr)
        return 2
    report = json.loads(report_path.read_text())
    solid = report["solids"][0]
    kinds: dict[str, int] = {}
    for f in solid["suppressed"]:
        kinds[f["kind"]] = kinds.get(f["kind"], 0) + 1
    timings = report["timings_s"]
    print(f"part: {solid['faces']} faces; midsurf found {kinds}")
    print(
        f"midsurf: recognition + both pairing passes {timings['pairing']:.3f} s; whole run {timings['total']:.2f} s "
        f"(wall {wall:.2f} s, load {timings['load']:.2f} s); result {report['result']['faces']} faces, "
        f"{report['topology']['components']} component(s), valid {report['result']['valid']}"
    )

    shape = read_step(part_path)
    faces = ShapeMap()
    TopExp.MapShapes_s(shape, TopAbs_FACE, faces)
    remove = TopTools_ListOfShape()
    count = 0
    for f in solid["suppressed"]:
        for face in f["faces"]:
            remove.Append(faces.FindKey(face + 1))
            count += 1
    started = time.perf_counter()
    defeature = BRepAlgoAPI_Defeaturing()
    defeature.SetShape(shape)
    defeature.AddFacesToRemove(remove)
    defeature.SetRunParallel(False)
    defeature.Build()
    occt = time.perf_counter() - started
    done = defeature.IsDone()
    left = None
    valid = False
    if done:
        result = ShapeMap()
        TopExp.MapShapes_s(defeature.Shape(), TopAbs_FACE, result)
        left = result.Size()
        valid = BRepCheck_Analyzer(defeature.Shape()).IsValid()
    print(f"OCCT BRepAlgoAPI_Defeaturing of the same {count} faces: {occt:.2f} s, done {done}, faces left {left}, valid {valid}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
