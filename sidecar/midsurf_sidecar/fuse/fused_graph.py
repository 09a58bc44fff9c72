"""The reply of `fuse`: each face of the fused shape with its patch and measurements, each edge with its faces,
length and points (what Rust's joint and trim decisions read)."""

from collections.abc import Sequence
from typing import Any

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.TopAbs import TopAbs_EDGE
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Shape

from ..constants import EDGE_POINTS
from ..geom.face_measure import measure
from ..geom.topology import IndexedShapeMap, bounds_face, indexed_map
from ..geom.vectors import xyz
from ..protocol.errors import KernelError, one_line


def describe(
    fused: TopoDS_Shape, face_map: IndexedShapeMap, patch_of: list[int], stem_ends: Sequence[TopoDS_Shape] = ()
) -> dict[str, Any]:
    """The reply's `faces` (face_map: the faces of F; patch_of: the patch of each) and `edges`; `stem_ends`: edges
    of F made by a cut across a stem's end (`patch_fuse._stem_end_cuts`), flagged `stem_end`."""
    edge_map = indexed_map(fused, TopAbs_EDGE)
    cut = {edge_map.FindIndex(edge) - 1 for edge in stem_ends} - {-1}
    edge_faces: list[list[int]] = [[] for _ in range(edge_map.Size())]
    edge_inside: list[list[int]] = [[] for _ in range(edge_map.Size())]
    faces = []
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        edges, seams, inside = _face_edges(face, edge_map)
        for e in edges:
            edge_faces[e].append(i)
            if e in seams:
                edge_faces[e].append(i)  # a seam joins the face to itself
            if e in inside:
                edge_inside[e].append(i)
        try:
            # A sliver of a fuse (two curved strips crossing at a grazing angle) may hold no point a classifier
            # finds inside: it is measured on its edge rather than failing the whole fuse, whose pass the
            # stitching keeps only when it leaves no more open length than it found.
            faces.append({"patch": patch_of[i], **measure(face, sliver_ok=True), "edges": edges})
        except Exception as exc:
            raise KernelError(f"fused face {i} (patch {patch_of[i]}): {one_line(exc)}") from exc
    edges_json = []
    for e in range(edge_map.Size()):
        try:
            edge = _describe_edge(TopoDS.Edge(edge_map.FindKey(e + 1)), edge_faces[e], edge_inside[e])
            edges_json.append({**edge, "stem_end": True} if e in cut else edge)
        except Exception as exc:
            raise KernelError(f"fused edge {e} (faces {edge_faces[e]}): {one_line(exc)}") from exc
    return {"faces": faces, "edges": edges_json}


def _face_edges(face: TopoDS_Shape, edge_map: IndexedShapeMap) -> tuple[list[int], set[int], set[int]]:
    """(edge indices of the face in explorer order, a seam once; the seams; the edges inside it). A seam is an
    edge the face uses twice (once each way). Not BRep_Tool.IsClosed: a piece of a split tube keeps both pcurves
    on the old seam edge although it uses it once, where it is a boundary like any other. An edge inside the
    face (INTERNAL or EXTERNAL) bounds nothing: a joint that ended inside the face without splitting it."""
    uses: dict[int, int] = {}
    inside: set[int] = set()
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        edge = explorer.Current()
        e = edge_map.FindIndex(edge) - 1
        uses[e] = uses.get(e, 0) + 1
        if not bounds_face(edge):
            inside.add(e)
        explorer.Next()
    return list(uses), {e for e, n in uses.items() if n > 1}, inside


def _describe_edge(edge: TopoDS_Edge, faces: list[int], inside: list[int]) -> dict[str, Any]:
    """Length, faces and points of the edge; `inside` (only when some face holds it inside) the faces that do."""
    extra = {"inside": inside} if inside else {}
    if BRep_Tool.Degenerated_s(edge):
        # No 3D curve: the edge is its vertex.
        point = list(xyz(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(edge))))
        return {"length": 0.0, "faces": faces, "points": [point] * EDGE_POINTS, **extra}
    curve = BRepAdaptor_Curve(edge)
    first, last = curve.FirstParameter(), curve.LastParameter()
    step = (last - first) / (EDGE_POINTS - 1)
    points = [list(xyz(curve.Value(first + k * step))) for k in range(EDGE_POINTS - 1)]
    points.append(list(xyz(curve.Value(last))))
    return {"length": GCPnts_AbscissaPoint.Length_s(curve), "faces": faces, "points": points, **extra}
