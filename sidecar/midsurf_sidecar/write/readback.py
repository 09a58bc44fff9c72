"""The STEP file as any reader sees it: read back and checked, face by face.

A face that fails BRepCheck in memory is often repaired by the reader's healing (its pcurves, its tolerances);
one that still fails once read back is broken for every user of the file. The check names those faces by their
index in the written shape: the reader's order when it read as many faces as were written (manifold shells read
back as written) when the broken face lies on the written face of that index, else the written face its edges
lie on.
"""

from dataclasses import dataclass

from OCP.Bnd import Bnd_Box
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.gp import gp_Pnt
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.BRep import BRep_Tool
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL
from OCP.TopoDS import TopoDS, TopoDS_Shape

from ..constants import READBACK_MATCH, UNBOUNDED_BOX
from ..geom.topology import bounded, curve_edges, distance_to, edge_uses, indexed_map, subshapes


@dataclass(frozen=True)
class Check:
    """What a reader makes of a written file."""

    valid: bool
    # Faces of the written shape (MapShapes order) whose read-back face fails BRepCheck or was dropped.
    invalid: list[int]
    # How many written faces the reader dropped (fewer faces read than written, or shells read back empty), and
    # how many of those could not be named.
    dropped: int = 0
    unnamed: int = 0
    # The largest edge tolerance read back: how far an edge may lie off its faces (a reader widens the tolerance
    # of an edge whose curve strays from them; a mesher's boundary nodes stray as far).
    max_edge_tolerance: float = 0.0
    # Edges of the file read back used by one face only (free; seams left out): more than the shape written has
    # when the reader rebuilt a face apart from the edges it shared.
    free_edges: int = 0


def check_written(path: str, shape: TopoDS_Shape) -> Check:
    """The file at `path` read back and checked against `shape`, the shape written. A file that cannot be read
    back counts as invalid with no face named. A written face without a wire is broken whatever BRepCheck says:
    it stands for its whole unbounded surface (an infinite plane), which no reader can mesh; so is a face the
    reader makes without one (it could not take the face's loops)."""
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        return Check(False, [])
    reader.TransferRoots()
    back = reader.OneShape()
    loose = max((BRep_Tool.Tolerance_s(TopoDS.Edge(e)) for e in subshapes(back, TopAbs_EDGE)), default=0.0)
    # Seams left out: the shells' faces closed on themselves are split before writing (no seam there), but a
    # solid kept as it is (`--keep-solids`) keeps its seams, which join its faces to themselves.
    free = edge_uses(back, seams_free=False)[0]
    own = indexed_map(shape, TopAbs_FACE)
    unbounded = {j for j in range(own.Size()) if not bounded(own.FindKey(j + 1))}
    back_faces = subshapes(back, TopAbs_FACE)
    if not unbounded and all(map(bounded, back_faces)) and BRepCheck_Analyzer(back).IsValid():
        return Check(True, [], max_edge_tolerance=loose, free_edges=free)
    bad = [k for k, face in enumerate(back_faces) if not bounded(face) or not BRepCheck_Analyzer(face).IsValid()]
    read_empty = _lost_faces(back, shape, own)
    dropped = max(len(read_empty), own.Size() - len(back_faces), 0)
    unnamed = dropped - len(read_empty)
    lost = read_empty | unbounded
    written = [own.FindKey(j + 1) for j in range(own.Size())]
    boxes = [_box(face) for face in written]
    extents = (max(abs(c) for c in box) for box in boxes if box is not None)
    size = max((e for e in extents if e < UNBOUNDED_BOX), default=1.0)
    reach = READBACK_MATCH * max(size, 1.0)
    same_count = len(back_faces) == own.Size()
    invalid = set(lost)
    for k in bad:
        # As many faces read as written: often face for face in the written order, but a reader may take the
        # shells apart and put their faces back in another order. The face in the same place is taken when the
        # broken face lies on it, else the face it lies on (naming another face would leave a sound face out
        # and keep the broken one, round after round); the same place again when it lies on none.
        if same_count and _holds(written[k], back_faces[k], reach):
            invalid.add(k)
            continue
        origin = _origin(back_faces[k], written, boxes, reach)
        if origin is None and same_count:
            origin = k
        if origin is not None:
            invalid.add(origin)
    return Check(False, sorted(invalid), dropped, unnamed, loose, free)


def _lost_faces(back: TopoDS_Shape, shape: TopoDS_Shape, own) -> set[int]:
    """The faces (MapShapes order of `shape`) of the written shells that read back empty: the reader could not
    take any of their faces. Shells read back in the order written, so they are matched by position when as
    many were read as written."""
    back_shells, shells = subshapes(back, TopAbs_SHELL), subshapes(shape, TopAbs_SHELL)
    if len(back_shells) != len(shells):
        return set()
    lost = set()
    for back_shell, shell in zip(back_shells, shells):
        if back_shell.NbChildren() == 0:
            lost.update(own.FindIndex(face) - 1 for face in subshapes(shell, TopAbs_FACE))
    return lost


def _origin(
    face: TopoDS_Shape, written: list[TopoDS_Shape], boxes: list[tuple[float, ...] | None], reach: float
) -> int | None:
    """The written face on which most of the midpoints of `face`'s edges lie (within `reach`); when none holds
    half of them (the reader rebuilt the face off its surface), the face nearest to them (by the median
    distance). A broken face often has an edge or two off its surface, which is why it is broken."""
    points = _edge_midpoints(face)
    if not points:
        return None
    # Only faces near the broken one can be its origin: their boxes reach its edges within its own size.
    own = _box(face)
    margin = reach + (max(own[i + 3] - own[i] for i in range(3)) if own is not None else 0.0)
    scored = []
    for j, box in enumerate(boxes):
        if box is None or not any(all(box[i] - margin <= p[i] <= box[i + 3] + margin for i in range(3)) for p in points):
            continue
        distances = sorted(_distance_to(written[j], p) for p in points)
        on = [d for d in distances if d <= reach]
        scored.append(((len(on), -sum(on)), -distances[len(distances) // 2], j))
    if not scored:
        return None
    best_on = max(scored)
    if best_on[0][0] * 2 >= len(points):
        return best_on[2]
    return max(scored, key=lambda s: s[1])[2]


def _holds(written: TopoDS_Shape, face: TopoDS_Shape, reach: float) -> bool:
    """Whether at least half the midpoints of `face`'s edges lie on `written` (within `reach`), as in `_origin`."""
    points = _edge_midpoints(face)
    return bool(points) and 2 * sum(_distance_to(written, p) <= reach for p in points) >= len(points)


# The broken face's edges sampled for its origin: a few suffice, the longest say the most.
ORIGIN_EDGES = 8


def _edge_midpoints(face: TopoDS_Shape) -> list[tuple[float, float, float]]:
    edges = []
    for edge in curve_edges(face):
        curve = BRepAdaptor_Curve(edge)
        first, last = curve.FirstParameter(), curve.LastParameter()
        a, m, b = curve.Value(first), curve.Value(0.5 * (first + last)), curve.Value(last)
        edges.append((a.Distance(m) + m.Distance(b), (m.X(), m.Y(), m.Z())))
    edges.sort(key=lambda e: -e[0])
    return [point for _, point in edges[:ORIGIN_EDGES]]


def _distance_to(face: TopoDS_Shape, point: tuple[float, float, float]) -> float:
    """`distance_to`, infinite when OCCT cannot tell (the point then holds no face)."""
    distance = distance_to(gp_Pnt(*point), face)
    return float("inf") if distance is None else distance


def _box(face: TopoDS_Shape) -> tuple[float, ...] | None:
    """(xmin, ymin, zmin, xmax, ymax, zmax); None for a face with nothing to bound (no surface, no edge with a
    curve: OCCT raises on the corners of its void box), which lies nowhere another face could be matched."""
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box)
    if box.IsVoid():
        return None
    low, high = box.CornerMin(), box.CornerMax()
    return (low.X(), low.Y(), low.Z(), high.X(), high.Y(), high.Z())
