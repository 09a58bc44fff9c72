"""FreeCAD round trip: does FreeCAD read midsurf's output as midsurf says it wrote it?

Run by FreeCAD's console (`freecadcmd`, Debian package freecad-python3), which runs a script but passes it no
arguments, so the work list comes in the environment:

  MIDSURF_ROUNDTRIP="OUT1.step:REPORT1.json OUT2.step:REPORT2.json" freecadcmd scripts/freecad_roundtrip.py
      reads each output with Part.read and compares it with its report: validity, faces, edges, vertices,
      connected components (faces joined by shared edges), non-manifold edges, free edges, total area.
  MIDSURF_ROUNDTRIP_MAKE=DIR freecadcmd scripts/freecad_roundtrip.py
      models a thin-walled part in FreeCAD (a tray: a hollowed box with a rib) and exports it as DIR/tray.step,
      for the other direction (FreeCAD -> midsurf).

Prints one line per file and writes "roundtrip: ok" or "roundtrip: FAILED" as the last line, with exit code
0 or 1 (freecadcmd itself exits 0 whatever a script does, hence the last line, which the caller reads).
"""

import json
import os
import sys

import FreeCAD  # noqa: F401  (sets FreeCAD's module path up)
import Part

# Relative tolerance on the total area: STEP stores geometry to full precision, so only rounding in the report
# (0.01 mm²), the reader's tolerance fixes and OCCT's area integration move it. The integration is the loosest:
# on a rational B-spline face running into a pole (a dome's mid-patch, 28.999 mm radius, exact area 3461.82 mm²)
# it gives 3462.46 in memory and 3462.01 on the faces read back (1.3e-4 apart); on a plane face whose hole is
# bounded by a curve the fuse cut it along (where a ramp following a spline outline meets it: fixture
# plate_pocket_spline), 5637.7 in memory and 5640.6 read back, 4.9e-4 of the part's 6016 mm². A face lost or
# broken moves the area by far more.
AREA_TOLERANCE = 1e-3


def counts(shape):
    """Topology of `shape` as our report counts it: edges and vertices shared between faces counted once."""
    faces = shape.Faces
    owners = {}  # edge hash -> faces using it (a seam edge counts once per face)
    degenerated = set()  # a sphere's or a cone's pole: a point, no free edge
    for i, face in enumerate(faces):
        for edge in face.Edges:
            owners.setdefault(edge.hashCode(), set()).add(i)
            if edge.Degenerated:
                degenerated.add(edge.hashCode())
    parent = list(range(len(faces)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for users in owners.values():
        users = sorted(users)
        for other in users[1:]:
            parent[root(other)] = root(users[0])
    return {
        "valid": shape.isValid(),
        "faces": len(faces),
        "edges": len(owners),
        "vertices": len({v.hashCode() for v in shape.Vertexes}),
        "components": len({root(i) for i in range(len(faces))}),
        "nonmanifold_edges": sum(1 for users in owners.values() if len(users) > 2),
        "free_edges": sum(1 for e, users in owners.items() if len(users) == 1 and e not in degenerated),
        "area": shape.Area,
    }


def expected(report):
    topology, result = report["topology"], report["result"]
    free = result.get("free_edges") or {}
    return {
        "valid": result["valid"],
        "faces": topology["faces"],
        "edges": topology["edges"],
        "vertices": topology["vertices"],
        "components": topology["components"],
        "nonmanifold_edges": topology["nonmanifold_edges"],
        "free_edges": topology["free_edge_count"] if free else None,
        "area": result["area"],
    }


def check(step, report_path):
    """(mismatches between FreeCAD's reading of `step` and the report, as text; what FreeCAD counted or None)."""
    if not os.path.isfile(step):
        return [f"no such file {step}"], None
    try:
        shape = Part.read(step)
    except Exception as exc:  # FreeCAD raises Part.OCCError or a bare Exception on unreadable files
        return [f"FreeCAD cannot read it: {exc}"], None
    with open(report_path) as f:
        want = expected(json.load(f))
    got = counts(shape)
    problems = []
    for key, value in want.items():
        if value is None:
            continue
        if key == "area":
            if abs(got[key] - value) > AREA_TOLERANCE * max(value, 1.0):
                problems.append(f"area {got[key]:.3f} != report {value:.3f}")
        elif got[key] != value:
            problems.append(f"{key} {got[key]} != report {value}")
    if not got["valid"]:
        problems.append("not valid in FreeCAD (Shape.isValid() is False)")
    return problems, got


def make_tray(directory):
    """A 2 mm tray (80 x 50 x 20, open top) with a 2 mm rib across its floor, modelled and exported by FreeCAD."""
    outer = Part.makeBox(80, 50, 20)
    inner = Part.makeBox(76, 46, 20, FreeCAD.Vector(2, 2, 2))
    rib = Part.makeBox(2, 46, 10, FreeCAD.Vector(39, 2, 2))
    tray = outer.cut(inner).fuse(rib).removeSplitter()
    path = os.path.join(directory, "tray.step")
    tray.exportStep(path)
    print(f"{path}: tray exported by FreeCAD, volume {tray.Volume:.1f}, {len(tray.Faces)} faces")
    return tray.isValid()


def main():
    make_dir = os.environ.get("MIDSURF_ROUNDTRIP_MAKE")
    if make_dir:
        return make_tray(make_dir)
    work = os.environ.get("MIDSURF_ROUNDTRIP", "").split()
    if not work:
        print("freecad_roundtrip: set MIDSURF_ROUNDTRIP='OUT.step:REPORT.json ...' or MIDSURF_ROUNDTRIP_MAKE=DIR")
        return False
    ok = True
    for item in work:
        step, _, report = item.rpartition(":")
        problems, got = check(step, report)
        if problems:
            ok = False
            print(f"{step}: FAILED: " + "; ".join(problems))
        else:
            print(
                f"{step}: ok (valid, {got['faces']} faces, {got['edges']} edges, {got['components']} component(s), "
                f"{got['nonmanifold_edges']} non-manifold and {got['free_edges']} free edges, area {got['area']:.2f})"
            )
    return ok


ok = main()
print("roundtrip: ok" if ok else "roundtrip: FAILED")
sys.stdout.flush()
if __name__ == "__main__":
    sys.exit(0 if ok else 1)
