"""`extend_edges`: a strip face grown from a free edge of a mid-patch, outward along the patch's tangent plane,
by a length Rust chose at each sample of the edge (the samples of `probe_edges`).

The strip is the ruled surface between the edge and its far curve (the sample points moved outward): flat
for a straight edge reaching a plane, twisted where the lengths vary along a curved edge. Its near edge
coincides with the patch's edge, so the next `fuse` shares it.
"""

from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepFill import BRepFill
from OCP.GC import GC_MakeSegment
from OCP.GeomAbs import GeomAbs_Line
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Pnt
from OCP.collections import HArray1_gp_Pnt
from OCP.TopAbs import TopAbs_FORWARD
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from .edge_probe import sample_edge
from .errors import KernelError
from .vectors import Vec, add_scaled, cross, norm, sub


def strip(face: TopoDS_Face, edge: TopoDS_Shape, lengths: list[float]) -> TopoDS_Face:
    samples = sample_edge(face, edge, len(lengths))
    far = [add_scaled(s.point, s.outward, length) for s, length in zip(samples, lengths)]
    # Forward, so the ruled surface joins the near edge's first vertex to the far curve's first point.
    near = TopoDS.Edge(edge.Oriented(TopAbs_FORWARD))
    near_curve = BRepAdaptor_Curve(near)
    tolerance = 1e-6 * max(norm(sub(far[-1], far[0])), max(lengths))
    if near_curve.GetType() == GeomAbs_Line and _collinear(far, tolerance):
        far_curve = GC_MakeSegment(gp_Pnt(*far[0]), gp_Pnt(*far[-1])).Value()
    else:
        points = HArray1_gp_Pnt(1, len(far))
        for k, p in enumerate(far):
            points.SetValue(k + 1, gp_Pnt(*p))
        interpolate = GeomAPI_Interpolate(points, False, tolerance)
        interpolate.Perform()
        if not interpolate.IsDone():
            raise KernelError("the strip's far curve could not be interpolated")
        far_curve = interpolate.Curve()
    far_edge = BRepBuilderAPI_MakeEdge(far_curve).Edge()
    result = BRepFill.Face_s(near, far_edge)
    if result.IsNull() or not BRepCheck_Analyzer(result).IsValid():
        raise KernelError("the strip face is not valid")
    return result


def _collinear(points: list[Vec], tolerance: float) -> bool:
    a, b = points[0], points[-1]
    axis = sub(b, a)
    length = norm(axis)
    if length == 0.0:
        return False
    return all(norm(cross(sub(p, a), axis)) / length <= tolerance for p in points)
