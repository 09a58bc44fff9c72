"""`midsurf mesh` decks read back by independent readers: pyNastran (.bdf), dynakw (.k), meshio plus a parser of
*SHELL SECTION (.inp). Each fixture goes through the real binary (`midsurf run`, then `midsurf mesh`); every
deck must hold the quality report's element count, give each element a thickness of its patch (area per
thickness band against the run report's patch areas), share the nodes of a T-joint among the elements of all
its patches (edges used by three elements, as long as the report's joint), leave no free mesh edge where the
mid-surface has none, and carry its shell volume within 2% of the run report's (patch area x thickness).

Needs target/release/midsurf (scripts/test builds it; MIDSURF_BIN overrides)."""

import json
import math
import os
import re
import subprocess
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("MIDSURF_BIN", ROOT / "target" / "release" / "midsurf"))

# pyNastran 1.4.1 (the last release) still calls np.in1d, which numpy 2.4 removed; np.isin is its successor.
if not hasattr(np, "in1d"):
    np.in1d = np.isin
from pyNastran.bdf.bdf import read_bdf  # noqa: E402
import dynakw  # noqa: E402
import meshio  # noqa: E402

# (fixture, target size, position): a T-joint, a thickness step (two bands), ribs on a box (T-joints), a bent
# sheet (curved; at 3 mm gmsh 4.15.2 leaves a few triangles among the quads, so the decks mix element types).
CASES = [("t_rib", 5.0, "mid"), ("plate_step", 5.0, "top"), ("open_box_ribs", 5.0, "bottom"), ("bent_sheet", 3.0, "mid")]


def mesh_case(tmp: Path, name: str, size: float, position: str):
    mid, report, base = tmp / f"{name}.mid.step", tmp / f"{name}.json", tmp / name
    subprocess.run(
        [BIN, "run", ROOT / "fixtures" / f"{name}.step", "-o", mid, "--report", report, "--no-timings",
         "--position", position],
        check=True, capture_output=True,
    )
    done = subprocess.run(
        [BIN, "mesh", mid, "--report", report, "-o", base, "--size", str(size)], capture_output=True, text=True
    )
    assert done.returncode in (0, 1), done.stderr
    return json.loads(report.read_text()), json.loads(Path(f"{base}.quality.json").read_text()), base


@pytest.fixture(scope="module", params=CASES, ids=[c[0] for c in CASES])
def case(request, tmp_path_factory):
    if not BIN.is_file():
        pytest.fail(f"{BIN} is missing: build it with cargo build --release (scripts/test does)")
    name, size, position = request.param
    run, quality, base = mesh_case(tmp_path_factory.mktemp(name), name, size, position)
    return {"name": name, "position": position, "run": run, "quality": quality, "base": base}


def polygon_area(points):
    """Area of a planar-ish polygon (Newell), as the decks' readers do not all give one."""
    n = np.zeros(3)
    for a, b in zip(points, points[1:] + points[:1]):
        n += np.cross(a, b)
    return 0.5 * float(np.linalg.norm(n))


def read_k(path):
    """(nodes {id: xyz}, elements [(node ids, thickness)], nloc per section) from an LS-DYNA deck, via dynakw."""
    nodes, raw, section_t, section_nloc, part_sec = {}, [], {}, {}, {}
    with dynakw.DynaKeywordReader(str(path)) as deck:
        for kw in deck.keywords():
            kind = type(kw).__name__
            if kind == "Node":
                c = kw.cards["Card 1"]
                for i, x, y, z in zip(c["NID"], c["X"], c["Y"], c["Z"]):
                    nodes[int(i)] = np.array([x, y, z], dtype=float)
            elif kind == "SectionShell":
                sec = int(kw.cards["Card 1"]["SECID"][0])
                section_t[sec] = float(kw.cards["Card 2"]["T1"][0])
                section_nloc[sec] = float(kw.cards["Card 2"]["NLOC"][0])
            elif kind == "Part":
                c = kw.cards["Card 2"]
                part_sec[int(c["PID"][0])] = int(c["SECID"][0])
            elif kind == "ElementShell":
                c = kw.cards["Card 1"]
                for pid, *ns in zip(c["PID"], c["N1"], c["N2"], c["N3"], c["N4"]):
                    ids = [int(n) for n in ns]
                    if ids[3] == ids[2]:  # a triangle repeats its third node
                        ids = ids[:3]
                    raw.append((ids, int(pid)))
    elements = [(ids, section_t[part_sec[pid]]) for ids, pid in raw]
    return nodes, elements, set(section_nloc.values())


def read_bdf_deck(path):
    model = read_bdf(str(path), xref=True, debug=None, punch=True)
    nodes = {nid: np.array(g.xyz, dtype=float) for nid, g in model.nodes.items()}
    elements, zoffs = [], set()
    for e in model.elements.values():
        assert e.type in ("CQUAD4", "CTRIA3"), e.type
        elements.append((list(e.node_ids), float(e.Thickness())))
        zoffs.add((round(float(e.zoffset or 0.0) / float(e.Thickness()), 6)))
    return nodes, elements, zoffs


def read_inp(path):
    """meshio for nodes, elements and element sets; the *SHELL SECTION cards (which meshio skips) parsed here."""
    mesh = meshio.read(str(path), file_format="abaqus")
    text = Path(path).read_text()
    thickness, offsets = {}, set()
    for m in re.finditer(r"^\*SHELL SECTION, ELSET=(\w+), MATERIAL=\w+(?:, OFFSET=(\w+))?\n([^,\n]+),", text, re.M):
        thickness[m.group(1)] = float(m.group(3))
        offsets.add(m.group(2) or "")
    # meshio renumbers points 0.. in file order; the elements' node ids become those indices.
    nodes = {i: np.array(p, dtype=float) for i, p in enumerate(mesh.points)}
    elements = []
    for name, blocks in mesh.cell_sets.items():
        if name not in thickness:
            continue
        for block, indices in enumerate(blocks):
            cells = mesh.cells[block].data
            for i in indices:
                elements.append(([int(n) for n in cells[i]], thickness[name]))
    return nodes, elements, offsets


READERS = {"k": read_k, "bdf": read_bdf_deck, "inp": read_inp}


def edge_use(elements):
    use = Counter()
    for ids, _ in elements:
        for a, b in zip(ids, ids[1:] + ids[:1]):
            use[(min(a, b), max(a, b))] += 1
    return use


def edge_length(nodes, edges):
    return sum(float(np.linalg.norm(nodes[a] - nodes[b])) for a, b in edges)


@pytest.mark.parametrize("fmt", ["k", "bdf", "inp"])
def test_deck_reads_back_with_counts_thickness_joints_and_mass(case, fmt):
    nodes, elements, placement = READERS[fmt](Path(f"{case['base']}.{fmt}"))
    q, run = case["quality"], case["run"]
    assert len(elements) == q["total"]["elements"] > 0
    assert sum(len(ids) == 3 for ids, _ in elements) == q["total"]["trias"]
    if case["name"] == "bent_sheet":
        assert q["total"]["trias"] > 0, "this case exists to mix triangles and quads in the decks"
    assert len(nodes) == q["nodes"]
    assert all(len(ids) in (3, 4) and len(set(ids)) == len(ids) for ids, _ in elements)

    # Thickness per element: the area of each thickness band equals the run's patch area with that thickness.
    band_area = defaultdict(float)
    for ids, t in elements:
        band_area[round(t, 3)] += polygon_area([nodes[i] for i in ids])
    want = defaultdict(float)
    for p in run["patches"]:
        want[round(p["thickness"]["mean"], 3)] += p["area"]
    assert set(band_area) == set(want), (band_area, want)
    for t, area in want.items():
        assert math.isclose(band_area[t], area, rel_tol=0.02), (t, band_area[t], area)

    # Mass: shell volume (area x thickness) within 2% of the mid-surface's (the judge's vol_ratio numerator).
    shell = sum(polygon_area([nodes[i] for i in ids]) * t for ids, t in elements)
    mid = sum(p["area"] * p["thickness"]["mean"] for p in run["patches"])
    assert math.isclose(shell, mid, rel_tol=0.02), (shell, mid)

    use = edge_use(elements)
    # No free mesh edge where the mid-surface has none: free length = the mid-surface's rim + open edges.
    free = run["result"]["free_edges"]
    free_length = edge_length(nodes, [e for e, n in use.items() if n == 1])
    assert math.isclose(free_length, free["rim_length"] + free["open_length"], rel_tol=0.01)
    # T-joints conform: the elements of all three patches share the joint's nodes, so the joint's edges are
    # used by three elements, along the whole joint length the run reports for the "t" joints that stay
    # non-manifold (a branch ending on a closed wall meets it along a manifold edge, not counted).
    t_length = edge_length(nodes, [e for e, n in use.items() if n >= 3])
    nonmanifold = run["topology"]["nonmanifold_edges"]
    if nonmanifold:
        joints = sum(j["length"] for j in run["joints"] if j["kind"] == "t")
        assert t_length > 0.5 * joints and math.isclose(t_length, q["total"]["t_edges"]["length"], rel_tol=1e-6)
    else:
        assert t_length == 0

    # The position reaches the solver: NLOC, ZOFFS / t, OFFSET.
    expected = {
        "k": {"mid": {0.0}, "top": {1.0}, "bottom": {-1.0}},
        "bdf": {"mid": {0.0}, "top": {-0.5}, "bottom": {0.5}},
        "inp": {"mid": {""}, "top": {"SPOS"}, "bottom": {"SNEG"}},
    }[fmt][case["position"]]
    assert placement == expected


def test_t_rib_joint_is_shared_by_the_elements_of_both_patches(case):
    if case["name"] != "t_rib":
        pytest.skip("the T-rib's joint only")
    nodes, elements, _ = read_k(Path(f"{case['base']}.k"))
    use = edge_use(elements)
    joint = [e for e, n in use.items() if n == 3]
    # The rib (x = 50) stands on the plate (z = 1) along y from 0 to 60.
    assert math.isclose(edge_length(nodes, joint), 60.0, rel_tol=1e-9)
    for a, b in joint:
        for p in (nodes[a], nodes[b]):
            assert abs(p[0] - 50.0) < 1e-9 and abs(p[2] - 1.0) < 1e-9
