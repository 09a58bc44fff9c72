"""Projection of one face onto a plane along the plane's normal (the mid-patch of a draft pair).

Every edge curve is projected with GeomProjLib.ProjectOnPlane (keepParametrization=False, so lines stay
lines; True, giving a B-spline, only where that exact projection misses the edge's ends) and rebuilt
between projected copies of the face's own vertices (shared vertices stay shared); the wires keep their
edge orientations, and the new face lies on the plane oriented like the source face: its normal is the
plane normal or its opposite, whichever points the way the source face's outward normal does.
"""

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Geom import Geom_Curve, Geom_Plane, Geom_TrimmedCurve
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.GeomProjLib import GeomProjLib
from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
from OCP.Precision import Precision
from OCP.ShapeFix import ShapeFix_Face
from OCP.TopAbs import TopAbs_EDGE, TopAbs_VERTEX
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire

from ..constants import EDGE_ON_COSINE, EDGE_ON_TANGENT, INFINITE_PARAMETER, MAX_VERTEX_MISS, PARAMETER_RESOLUTION, VERTEX_MISS_MARGIN
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import interior_point
from ..geom.topology import diagonal, face_wires, indexed_map
from ..geom.vectors import Vec, add_scaled, dot, norm, scale, sub, xyz
from ..protocol.errors import OpError


def project_face(face: TopoDS_Face, origin: Vec, normal: Vec) -> TopoDS_Face:
    """`face` projected onto the plane (origin, unit normal). Raises OpError `patch_failed`."""
    _, source_normal = interior_point(OutwardNormals(face), diagonal(face))
    facing = dot(source_normal, normal)
    if abs(facing) < EDGE_ON_COSINE:
        raise OpError(
            f"face is edge-on to the plane (its normal . plane normal = {facing:.2g}): nothing to project",
            "patch_failed",
        )
    side = normal if facing > 0 else scale(normal, -1.0)
    plane = gp_Pln(gp_Pnt(*origin), gp_Dir(*side))
    projected = _build_face(face, _Projector(face, plane), plane)
    if not BRepCheck_Analyzer(projected).IsValid():
        projected = _fixed(projected)
    _, new_normal = interior_point(OutwardNormals(projected), diagonal(projected))
    if dot(new_normal, side) <= 0:
        raise OpError("the projected outline folds over (the face turns away from the plane)", "patch_failed")
    return projected


def _build_face(face: TopoDS_Face, projector: "_Projector", plane: gp_Pln) -> TopoDS_Face:
    wires = [projector.wire(w) for w in face_wires(face)]
    if not wires:
        raise OpError("the face has no boundary wire", "patch_failed")
    maker = BRepBuilderAPI_MakeFace(plane, wires[0], True)
    if not maker.IsDone():
        raise OpError(f"no face from the projected outer wire ({maker.Error().name})", "patch_failed")
    for hole in wires[1:]:
        maker.Add(hole)
    return maker.Face()


def _fixed(face: TopoDS_Face) -> TopoDS_Face:
    fixer = ShapeFix_Face(face)
    fixer.Perform()
    fixed = fixer.Face()
    if fixed.IsNull() or not BRepCheck_Analyzer(fixed).IsValid():
        raise OpError("the projected face is invalid, even after ShapeFix_Face", "patch_failed")
    return fixed


class _Missed(OpError):
    """A projected curve does not pass through its projected vertex."""

    def __init__(self, message: str) -> None:
        super().__init__(message, "patch_failed")


class _Projector:
    """Projects the vertices and edges of one face, each once, so the new wires share them."""

    def __init__(self, face: TopoDS_Face, plane: gp_Pln) -> None:
        self.geom_plane = Geom_Plane(plane)
        self.direction = plane.Axis().Direction()
        self.origin = xyz(plane.Location())
        self.normal = xyz(self.direction)
        self.builder = BRep_Builder()
        self.vertex_map = indexed_map(face, TopAbs_VERTEX)
        self.edge_map = indexed_map(face, TopAbs_EDGE)
        self.vertices: dict[int, TopoDS_Vertex] = {}
        self.edges: dict[int, TopoDS_Edge] = {}

    def wire(self, wire: TopoDS_Wire) -> TopoDS_Wire:
        new_wire = TopoDS_Wire()
        self.builder.MakeWire(new_wire)
        explorer = TopExp_Explorer(wire, TopAbs_EDGE)
        while explorer.More():
            edge = TopoDS.Edge(explorer.Current())
            # A degenerate edge (cone apex, sphere pole) is a point: its neighbours already meet there.
            if not BRep_Tool.Degenerated_s(edge):
                # The same edge in the same direction, on the plane.
                self.builder.Add(new_wire, self._edge(edge).Oriented(edge.Orientation()))
            explorer.Next()
        new_wire.Closed(BRep_Tool.IsClosed_s(wire))
        return new_wire

    def _edge(self, edge: TopoDS_Edge) -> TopoDS_Edge:
        index = self.edge_map.FindIndex(edge)
        if index not in self.edges:
            self.edges[index] = self._project_edge(edge)
        return self.edges[index]

    def _project_edge(self, edge: TopoDS_Edge) -> TopoDS_Edge:
        curve = BRep_Tool.Curve_s(edge, 0.0, 0.0)
        if curve is None:
            raise OpError("an edge of the face has no 3D curve", "patch_failed")
        first, last = BRep_Tool.Range_s(edge)
        # TopExp without cumulated orientation: the vertices at the curve's first and last parameters.
        v1 = self._vertex(TopExp.FirstVertex_s(edge))
        v2 = self._vertex(TopExp.LastVertex_s(edge))
        try:
            basis, (p1, miss1), (p2, miss2) = self._bounded(curve, first, last, v1, v2, False)
        except _Missed:
            # ProjLib's exact projection of a hyperbola can miss by tenths of a mm on a large part; the
            # approximation that keeps the parametrisation (a B-spline) stays within ~1e-4.
            basis, (p1, miss1), (p2, miss2) = self._bounded(curve, first, last, v1, v2, True)
        for vertex, miss in ((v1, miss1), (v2, miss2)):
            if miss > BRep_Tool.Tolerance_s(vertex):
                # So that MakeEdge accepts the vertex where the curve ends.
                self.builder.UpdateVertex(vertex, VERTEX_MISS_MARGIN * miss)
        maker = BRepBuilderAPI_MakeEdge(basis, v1, v2, p1, p2)
        if not maker.IsDone():
            raise OpError(f"cannot rebuild a projected edge ({maker.Error().name})", "patch_failed")
        return maker.Edge()

    def _bounded(
        self, curve: Geom_Curve, first: float, last: float, v1: TopoDS_Vertex, v2: TopoDS_Vertex, keep: bool
    ) -> tuple[Geom_Curve, tuple[float, float], tuple[float, float]]:
        """(projected curve, (parameter, miss) at v1, at v2), the curve running from v1 to v2."""
        projected = GeomProjLib.ProjectOnPlane_s(
            Geom_TrimmedCurve(curve, first, last), self.geom_plane, self.direction, keep
        )
        # ProjLib trims a conic whose sense the projection flips on the wrong arc (a quarter circle becomes
        # three quarters of an ellipse): keep the projected curve, find the edge's bounds on it here.
        basis = projected.BasisCurve() if isinstance(projected, Geom_TrimmedCurve) else projected
        if not self._same_sense(curve, first, last, basis):
            basis = basis.Reversed()
        (p1, miss1), (p2, miss2) = self._parameter(basis, v1), self._parameter(basis, v2)
        if basis.IsPeriodic():
            # p2 within (p1, p1 + period]: a closed edge (one vertex) goes once round.
            period = basis.Period()
            p2 = p1 + (p2 - p1) % period
            if p2 - p1 <= PARAMETER_RESOLUTION * period:
                p2 += period
        elif v1.IsSame(v2):
            # A closed edge on a bounded, non-periodic curve (a closed B-spline): the whole curve.
            p1, p2 = basis.FirstParameter(), basis.LastParameter()
        elif p2 <= p1:
            raise OpError("a projected edge runs backwards along its curve", "patch_failed")
        return basis, (p1, miss1), (p2, miss2)

    def _same_sense(self, curve: Geom_Curve, first: float, last: float, projected: Geom_Curve) -> bool:
        """Whether `projected` runs the way the original curve does, from the tangents at the start
        (or, where the start tangent is along the projection direction, from the middle of the edge)."""
        for t in (first, 0.5 * (first + last)):
            tangent = self._in_plane(xyz(curve.DN(t, 1)))
            if norm(tangent) > EDGE_ON_TANGENT * norm(xyz(curve.DN(t, 1))):
                point = self._on_plane(xyz(curve.Value(t)))
                u = GeomAPI_ProjectPointOnCurve(gp_Pnt(*point), projected).LowerDistanceParameter()
                return dot(tangent, xyz(projected.DN(u, 1))) >= 0.0
        raise OpError("an edge of the face runs along the projection direction", "patch_failed")

    def _parameter(self, curve: Geom_Curve, vertex: TopoDS_Vertex) -> tuple[float, float]:
        """(parameter, distance) of the point of `curve` nearest `vertex`. Real files leave gaps between
        curve ends and vertices, covered by the vertex tolerance (which the projected vertex inherits);
        a miss beyond it and MAX_VERTEX_MISS raises _Missed."""
        point = BRep_Tool.Pnt_s(vertex)
        projector = GeomAPI_ProjectPointOnCurve(point, curve)
        count = projector.NbPoints()
        candidates = [(projector.Distance(i), projector.Parameter(i)) for i in range(1, count + 1)]
        # A vertex a little beyond the end of a bounded curve has no orthogonal projection on it.
        for end in (curve.FirstParameter(), curve.LastParameter()):
            if abs(end) < INFINITE_PARAMETER:
                candidates.append((curve.Value(end).Distance(point), end))
        if not candidates:
            raise _Missed("a projected vertex is not on its projected edge")
        miss, parameter = min(candidates)
        tolerance = BRep_Tool.Tolerance_s(vertex)
        if miss > max(tolerance, MAX_VERTEX_MISS):
            raise _Missed(f"a projected edge misses its vertex by {miss:.3g} mm (tolerance {tolerance:.3g})")
        return parameter, miss

    def _in_plane(self, vector: Vec) -> Vec:
        return sub(vector, scale(self.normal, dot(vector, self.normal)))

    def _on_plane(self, point: Vec) -> Vec:
        return add_scaled(point, self.normal, -dot(sub(point, self.origin), self.normal))

    def _vertex(self, vertex: TopoDS_Vertex) -> TopoDS_Vertex:
        index = self.vertex_map.FindIndex(vertex)
        if index not in self.vertices:
            new_vertex = TopoDS_Vertex()
            tolerance = max(BRep_Tool.Tolerance_s(vertex), Precision.Confusion_s())
            on_plane = self._on_plane(xyz(BRep_Tool.Pnt_s(vertex)))
            self.builder.MakeVertex(new_vertex, gp_Pnt(*on_plane), tolerance)
            self.vertices[index] = new_vertex
        return self.vertices[index]
