"""Convexity of an edge between two faces, from the outward normals on both sides (KERNEL_NOTES method)."""

import math
import statistics

from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopoDS import TopoDS_Edge

from ..constants import CONVEXITY_SAMPLES, SMOOTH_ANGLE
from ..geom.face_normals import OutwardNormals
from ..geom.vectors import cross, dot, norm, scale, xyz

def dihedral_angle(
    edge: TopoDS_Edge,
    curve: BRepAdaptor_Curve,
    reversed_in_f1: bool,
    f1: OutwardNormals,
    f2: OutwardNormals,
) -> float | None:
    """Signed angle between the outward normals of f1 and f2 across `edge`: > 0 convex, < 0 concave.

    At each sample ang = atan2((n1 x n2) . t1, n1 . n2), t1 the edge tangent as the edge runs in f1
    (f1's boundary runs counter-clockwise seen from outside, so n1 x t1 points into f1). The median of
    the samples is kept so one bad sample cannot flip the answer; None when no sample was usable.
    """
    pcurve1 = BRepAdaptor_Curve2d(edge, f1.face)
    pcurve2 = BRepAdaptor_Curve2d(edge, f2.face)
    first, last = curve.FirstParameter(), curve.LastParameter()
    angles = []
    for fraction in CONVEXITY_SAMPLES:
        t = first + fraction * (last - first)
        point, derivative = gp_Pnt(), gp_Vec()
        curve.D1(t, point, derivative)
        tangent = xyz(derivative)
        length = norm(tangent)
        side1 = f1.at(*_uv(pcurve1, t))
        side2 = f2.at(*_uv(pcurve2, t))
        if length == 0 or side1 is None or side2 is None:
            continue
        tangent = scale(tangent, (-1.0 if reversed_in_f1 else 1.0) / length)
        n1, n2 = side1[1], side2[1]
        angles.append(math.atan2(dot(cross(n1, n2), tangent), dot(n1, n2)))
    return statistics.median(angles) if angles else None


def _uv(pcurve: BRepAdaptor_Curve2d, t: float) -> tuple[float, float]:
    # Edges are same-parameter: the 3D parameter is valid on the pcurve.
    p = pcurve.Value(t)
    return p.X(), p.Y()


def classify(angle: float) -> str:
    if abs(angle) < SMOOTH_ANGLE:
        return "smooth"
    return "convex" if angle > 0 else "concave"
