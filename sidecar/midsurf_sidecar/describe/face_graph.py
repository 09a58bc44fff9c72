"""`describe`: the face graph of a solid (faces, loops, edges with convexity, vertices, optional mesh)."""

from typing import Any

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
from OCP.Bnd import Bnd_Box
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.GeomAbs import (
    GeomAbs_BezierCurve,
    GeomAbs_BSplineCurve,
    GeomAbs_Circle,
    GeomAbs_Ellipse,
    GeomAbs_Line,
)
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED, TopAbs_VERTEX
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Wire

from ..geom.face_normals import OutwardNormals
from ..geom.face_point import interior_point
from ..geom.topology import IndexedShapeMap, face_wires, indexed_map, surface_props, volume
from ..geom.vectors import Vec, bbox_json, norm, sub, xyz
from ..protocol.errors import KernelError, one_line
from .edge_convexity import classify, dihedral_angle
from .face_mesh import face_mesh, mesh_shape, no_mesh
from .surface_kind import describe_surface

CURVE_KINDS = {
    GeomAbs_Line: "line",
    GeomAbs_Circle: "circle",
    GeomAbs_Ellipse: "ellipse",
    GeomAbs_BSplineCurve: "bspline",
    # A Bezier curve is a single-span B-spline; Rust treats both as free-form.
    GeomAbs_BezierCurve: "bspline",
}


class FaceEdgeUse:
    """How the edges of a solid are used by its faces: who bounds whom, and in which direction."""

    def __init__(self, n_edges: int) -> None:
        self.faces: list[list[int]] = [[] for _ in range(n_edges)]
        self.reversed_in: list[dict[int, bool]] = [{} for _ in range(n_edges)]
        self.seam: list[bool] = [False] * n_edges

    def record(self, edge: int, face: int, reversed_edge: bool) -> None:
        if face in self.reversed_in[edge]:
            # The same edge twice in one face: the closing seam of a periodic surface.
            self.seam[edge] = True
            return
        self.faces[edge].append(face)
        self.reversed_in[edge][face] = reversed_edge


def describe(solid: TopoDS_Shape, mesh_tolerance: float | None) -> dict[str, Any]:
    """The protocol's `describe` answer; `mesh_tolerance` None means no meshes."""
    face_map = indexed_map(solid, TopAbs_FACE)
    edge_map = indexed_map(solid, TopAbs_EDGE)
    vertex_map = indexed_map(solid, TopAbs_VERTEX)
    if mesh_tolerance is not None:
        mesh_shape(solid, mesh_tolerance)

    uses = FaceEdgeUse(edge_map.Size())
    normals: list[OutwardNormals] = []
    faces = []
    # The union of the face boxes: as tight as AddOptimal on the solid, without measuring every face twice.
    solid_box = Bnd_Box()
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        try:
            face_normals = OutwardNormals(face)
            face_box = _bbox(face)
        except Exception as exc:
            raise KernelError(f"face {i}: {one_line(exc)}") from exc
        with_mesh = mesh_tolerance is not None
        try:
            faces.append(_describe_face(i, face, face_normals, face_box, edge_map, uses, with_mesh))
        except Exception as exc:
            # One face the kernel cannot mesh or find a point in must not sink the part: it is described
            # as far as it can be, with the reason, and Rust leaves it out of pairing (and says so).
            try:
                faces.append(
                    _degraded_face(i, face, face_normals, face_box, edge_map, uses, with_mesh, one_line(exc))
                )
            except Exception:
                raise KernelError(f"face {i}: {one_line(exc)}") from exc
        normals.append(face_normals)
        solid_box.Add(face_box)

    edges = []
    for e in range(edge_map.Size()):
        edge = TopoDS.Edge(edge_map.FindKey(e + 1))
        try:
            edges.append(_describe_edge(e, edge, vertex_map, uses, normals))
        except Exception as exc:
            # An edge whose convexity cannot be sampled is kept (smooth, so nothing is built on it) and its
            # faces carry the reason: they are left out of pairing like a face that cannot be described.
            reason = f"edge {e}: {one_line(exc)}"
            described = _degraded_edge(e, edge, vertex_map, uses)
            if described is None:
                raise KernelError(f"edge {e} (faces {sorted(uses.faces[e])}): {one_line(exc)}") from exc
            edges.append(described)
            for f in described["faces"]:
                faces[f].setdefault("problem", reason)

    props = surface_props(solid)
    return {
        "volume": volume(solid),
        "area": props.Mass(),
        "bbox": bbox_json(solid_box),
        "vertices": [list(xyz(BRep_Tool.Pnt_s(TopoDS.Vertex(vertex_map.FindKey(v + 1)))))
                     for v in range(vertex_map.Size())],
        "faces": faces,
        "edges": edges,
    }


def _describe_face(
    index: int,
    face: TopoDS_Face,
    normals: OutwardNormals,
    box: Bnd_Box,
    edge_map: IndexedShapeMap,
    uses: FaceEdgeUse,
    with_mesh: bool,
) -> dict[str, Any]:
    diagonal = norm(sub(xyz(box.CornerMax()), xyz(box.CornerMin())))
    point, normal = interior_point(normals, diagonal)
    surface = describe_surface(normals.adaptor, normals.reversed, point, normal)
    described = _face_record(index, face, normals, box, surface, list(point), list(normal))
    if with_mesh:
        described["mesh"] = face_mesh(face, normals.reversed)
    # Last: recording the edge uses is the one side effect, and must happen once even if this face fails.
    described["loops"] = _loops(index, face, edge_map, uses)
    return described


def _face_record(
    index: int,
    face: TopoDS_Face,
    normals: OutwardNormals,
    box: Bnd_Box,
    surface: dict[str, Any],
    point: list[float],
    normal: list[float],
) -> dict[str, Any]:
    """What every described face carries, whole or degraded."""
    props = surface_props(face)
    return {
        "id": index,
        "surface": surface,
        "reversed": normals.reversed,
        "point": point,
        "normal": normal,
        "area": props.Mass(),
        "centroid": list(xyz(props.CentreOfMass())),
        "bbox": bbox_json(box),
    }


def _degraded_face(
    index: int,
    face: TopoDS_Face,
    normals: OutwardNormals,
    box: Bnd_Box,
    edge_map: IndexedShapeMap,
    uses: FaceEdgeUse,
    with_mesh: bool,
    problem: str,
) -> dict[str, Any]:
    """A face `_describe_face` failed on, as far as it can be described: its loops (so the graph stays whole),
    area and box, a stand-in point (the UV centre, even outside the trim, else the box centre) and whatever
    mesh exists (else none: no triangles)."""
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    sample = None
    try:
        sample = normals.at(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    except Exception:
        sample = None
    centre = list(0.5 * (a + b) for a, b in zip(xyz(box.CornerMin()), xyz(box.CornerMax())))
    point, normal = (list(sample[0]), list(sample[1])) if sample is not None else (centre, [0.0, 0.0, 1.0])
    try:
        surface = describe_surface(normals.adaptor, normals.reversed, tuple(point), tuple(normal))
    except Exception:
        surface = {"kind": "other"}
    described = _face_record(index, face, normals, box, surface, point, normal)
    described["loops"] = _loops(index, face, edge_map, uses)
    described["problem"] = problem
    if with_mesh:
        try:
            described["mesh"] = face_mesh(face, normals.reversed)
        except Exception:
            described["mesh"] = no_mesh()
    return described


def _degraded_edge(
    index: int, edge: TopoDS_Edge, vertex_map: IndexedShapeMap, uses: FaceEdgeUse
) -> dict[str, Any] | None:
    """An edge whose convexity could not be found, as smooth with angle 0; None without two vertices."""
    first = vertex_map.FindIndex(TopExp.FirstVertex_s(edge)) - 1
    last = vertex_map.FindIndex(TopExp.LastVertex_s(edge)) - 1
    if first < 0 or last < 0:
        return None
    a, b = xyz(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(edge))), xyz(BRep_Tool.Pnt_s(TopExp.LastVertex_s(edge)))
    try:
        curve = BRepAdaptor_Curve(edge)
        length = GCPnts_AbscissaPoint.Length_s(curve)
        kind = CURVE_KINDS.get(curve.GetType(), "other")
        midpoint = list(_midpoint(curve, kind, length))
    except Exception:
        length, kind, midpoint = norm(sub(b, a)), "other", [0.5 * (p + q) for p, q in zip(a, b)]
    return {"id": index, "vertices": [first, last], "faces": sorted(uses.faces[index]), "convexity": "smooth",
            "angle": 0.0, "length": length, "curve": kind, "midpoint": midpoint}


def _loops(index: int, face: TopoDS_Face, edge_map: IndexedShapeMap, uses: FaceEdgeUse) -> list[list[int]]:
    """Edge ids of each wire, outer wire first; records each edge use in `uses` on the way."""
    # Edge orientations in these wires are the ones the boundary really runs in (what convexity needs).
    wires = face_wires(face)

    loops = []
    for wire in wires:
        stored_order = []
        explorer = TopExp_Explorer(wire, TopAbs_EDGE)
        while explorer.More():
            edge = explorer.Current()
            edge_id = edge_map.FindIndex(edge) - 1
            uses.record(edge_id, index, edge.Orientation() == TopAbs_REVERSED)
            stored_order.append(edge_id)
            explorer.Next()
        connected = _connected_order(wire, face, edge_map)
        # BRepTools_WireExplorer skips edges of wires it cannot chain (non-manifold, gaps): the
        # stored order still lists every edge.
        loops.append(connected if len(connected) == len(stored_order) else stored_order)
    return loops


def _connected_order(wire: TopoDS_Wire, face: TopoDS_Face, edge_map: IndexedShapeMap) -> list[int]:
    ids = []
    explorer = BRepTools_WireExplorer(wire, face)
    while explorer.More():
        ids.append(edge_map.FindIndex(explorer.Current()) - 1)
        explorer.Next()
    return ids


def _describe_edge(
    index: int,
    edge: TopoDS_Edge,
    vertex_map: IndexedShapeMap,
    uses: FaceEdgeUse,
    normals: list[OutwardNormals],
) -> dict[str, Any]:
    first = vertex_map.FindIndex(TopExp.FirstVertex_s(edge)) - 1
    last = vertex_map.FindIndex(TopExp.LastVertex_s(edge)) - 1
    if first < 0 or last < 0:
        raise KernelError("edge without two vertices (infinite edge)")
    faces = sorted(uses.faces[index])
    described: dict[str, Any] = {"id": index, "vertices": [first, last], "faces": faces}

    if BRep_Tool.Degenerated_s(edge):
        # A collapsed edge (cone apex, sphere pole) has no 3D curve: it is its vertex.
        vertex = xyz(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(edge)))
        described.update(convexity="degenerate", angle=0.0, length=0.0, curve="other", midpoint=list(vertex))
        return described

    curve = BRepAdaptor_Curve(edge)
    convexity, angle = _convexity(index, edge, curve, faces, uses, normals)
    length = GCPnts_AbscissaPoint.Length_s(curve)
    kind = CURVE_KINDS.get(curve.GetType(), "other")
    described.update(convexity=convexity, angle=angle, length=length, curve=kind,
                     midpoint=list(_midpoint(curve, kind, length)))
    return described


def _convexity(
    index: int,
    edge: TopoDS_Edge,
    curve: BRepAdaptor_Curve,
    faces: list[int],
    uses: FaceEdgeUse,
    normals: list[OutwardNormals],
) -> tuple[str, float]:
    if len(faces) < 2:
        return ("seam" if uses.seam[index] else "free"), 0.0
    # A manifold edge has exactly two faces; on a non-manifold one the two lowest ids are compared.
    f1, f2 = faces[0], faces[1]
    angle = dihedral_angle(edge, curve, uses.reversed_in[index][f1], normals[f1], normals[f2])
    if angle is None:
        raise KernelError(f"no usable sample for convexity between faces {f1} and {f2}")
    return classify(angle), angle


def _midpoint(curve: BRepAdaptor_Curve, kind: str, length: float) -> Vec:
    first, last = curve.FirstParameter(), curve.LastParameter()
    if kind in ("line", "circle"):
        # Uniform parametrisation: the middle parameter is the middle of the arc length.
        return xyz(curve.Value(0.5 * (first + last)))
    return xyz(curve.Value(GCPnts_AbscissaPoint(curve, 0.5 * length, first).Parameter()))


def _bbox(shape: TopoDS_Shape) -> Bnd_Box:
    """Tight box from the exact geometry (not the mesh, not enlarged by tolerances)."""
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    return box
