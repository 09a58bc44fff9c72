"""Straight lines in a face's parameters, clipped to the face in those parameters.

A boolean Common of such a line's edge with its face finds the same pieces, but as a 3D problem: the edge lies
on the face, so the kernel intersects an approximated 3D curve with the face's surface all along it (0.2 s a
line on a B-spline face). In the face's parameters the pieces are where the line crosses the face's boundary
pcurves, found by a 2D curve intersection, and which gaps between crossings lie inside, found by classifying
their middles.
"""

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve2d
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepLib import BRepLib
from OCP.Geom2d import Geom2d_Line, Geom2d_TrimmedCurve
from OCP.Geom2dAPI import Geom2dAPI_InterCurveCurve
from OCP.TopAbs import TopAbs_IN
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Dir2d, gp_Pnt2d

from ..constants import CONFUSION, PARAMETRIC_CONFUSION
from .topology import bounds_face, curve_edges

# A crossing the 2D intersection reports lies on the line to its tolerance; a boundary vertex this close to the
# line ends an overlap of the line with the boundary.
ON_LINE = 10 * PARAMETRIC_CONFUSION


def line_within(face: TopoDS_Face, start: gp_Pnt2d, direction: gp_Dir2d, length: float) -> list[TopoDS_Shape]:
    """The pieces of the segment `start` + s `direction`, s in [0, length] of `face`'s parameters, that lie in
    `face`, as edges on its surface (with 3D curves), in order along the segment."""
    line = Geom2d_Line(start, direction)
    segment = Geom2d_TrimmedCurve(line, 0.0, length)
    cuts = {0.0, length}
    for edge in curve_edges(face):
        if not bounds_face(edge):
            continue
        pcurve = BRepAdaptor_Curve2d(edge, face)
        first, last = pcurve.FirstParameter(), pcurve.LastParameter()
        boundary = Geom2d_TrimmedCurve(pcurve.Curve(), first, last)
        crossing = Geom2dAPI_InterCurveCurve(segment, boundary, PARAMETRIC_CONFUSION)
        crossings = [crossing.Point(k) for k in range(1, crossing.NbPoints() + 1)]
        # Where the line runs along the boundary (an overlap), its pieces end at the boundary's vertices.
        ends = [pcurve.Value(first), pcurve.Value(last)] if crossing.NbSegments() else []
        for point in crossings + ends:
            if line.Distance(point) <= ON_LINE:
                cuts.add((point.X() - start.X()) * direction.X() + (point.Y() - start.Y()) * direction.Y())
    ordered = sorted(s for s in cuts if 0.0 <= s <= length)
    tolerance = BRep_Tool.Tolerance_s(face)
    inside: list[tuple[float, float]] = []
    for a, b in zip(ordered, ordered[1:]):
        if b - a <= PARAMETRIC_CONFUSION:
            continue
        middle = line.Value((a + b) / 2)
        if BRepClass_FaceClassifier(face, middle, tolerance).State() != TopAbs_IN:
            continue
        if inside and a - inside[-1][1] <= PARAMETRIC_CONFUSION:
            inside[-1] = (inside[-1][0], b)
        else:
            inside.append((a, b))
    surface = BRep_Tool.Surface_s(face)
    pieces = []
    for a, b in inside:
        maker = BRepBuilderAPI_MakeEdge(line, surface, a, b)
        if maker.IsDone() and b - a > CONFUSION:
            edge = maker.Edge()
            BRepLib.BuildCurves3d_s(edge)
            pieces.append(edge)
    return pieces
