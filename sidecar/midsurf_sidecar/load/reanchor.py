"""Planes, cylinders and cones whose parametric origin lies far from their face, given an origin at the face.

Some CAD exports place every cylinder's axis point far out along its axis (half a kilometre in a 40 mm part),
so the face's parameters are huge next to its size. The face is exact, but OCCT's 2D algorithms are not: the
pcurves a split computes on such a face come out with edge tolerances of millimetres, and every later fuse of
the patches fails on them (an area check finds loops turned inside out). Moving the surface's origin to the
middle of the face's parameter box is a translation of its parameters: the surface is unchanged, and each
pcurve of the face is translated by the same amount, so every edge stays exactly where it was."""

import math

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepTools import BRepTools
from OCP.Bnd import Bnd_Box
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Plane
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Vec, gp_Vec2d

from ..constants import ANCHOR_FAR
from ..geom.topology import indexed_map


def reanchored(solid: TopoDS_Shape) -> TopoDS_Shape:
    """`solid` with every plane, cylinder and cone face whose parametric origin lies more than ANCHOR_FAR times
    the face's size from the face given an origin at the middle of its parameter box. Edited in place: the
    caller hands over a solid of its own."""
    explorer = TopExp_Explorer(solid, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        explorer.Next()
        shift = _shift(face)
        if shift is not None:
            translate_parameters(face, *shift)
    return solid


def _shift(face: TopoDS_Face) -> tuple[float, float] | None:
    """(du, dv) to move the origin of `face`'s parameters by, None when the face is near enough or another kind.
    A cylinder's or a cone's u is an angle: only v, a length along the axis or the ruling, moves."""
    kind = BRepAdaptor_Surface(face, False).GetType()
    if kind not in (GeomAbs_Plane, GeomAbs_Cylinder, GeomAbs_Cone):
        return None
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    du = 0.5 * (u0 + u1) if kind == GeomAbs_Plane else 0.0
    dv = 0.5 * (v0 + v1)
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box)
    if box.IsVoid() or max(abs(du), abs(dv)) <= ANCHOR_FAR * math.sqrt(box.SquareExtent()):
        return None
    return du, dv


def translate_parameters(face: TopoDS_Face, du: float, dv: float) -> None:
    """The face (a plane, cylinder or cone) moved onto a copy of its surface whose parameters are those of the
    old minus (du, dv), with its pcurves translated to match; `du` only moves a plane's (a cylinder's or a
    cone's u is an angle). Nothing changed for another surface or when the surface refuses the move (a cone
    past its apex)."""
    kind = BRepAdaptor_Surface(face, False).GetType()
    if kind not in (GeomAbs_Plane, GeomAbs_Cylinder, GeomAbs_Cone):
        return
    if kind != GeomAbs_Plane:
        du = 0.0
    location = TopLoc_Location()
    surface = BRep_Tool.Surface_s(face, location).Copy()
    position = surface.Position()
    if kind == GeomAbs_Plane:
        position.Translate(gp_Vec(position.XDirection()) * du + gp_Vec(position.YDirection()) * dv)
    elif kind == GeomAbs_Cylinder:
        position.Translate(gp_Vec(position.Direction()) * dv)
    else:
        angle = surface.SemiAngle()
        radius = surface.RefRadius() + dv * math.sin(angle)
        if radius < 0.0:
            return
        position.Translate(gp_Vec(position.Direction()) * (dv * math.cos(angle)))
        surface.SetRadius(radius)
    surface.SetPosition(position)
    # Pcurves are asked of the forward face: on a reversed one OCCT swaps a seam's two, which UpdateEdge takes
    # forward's first.
    forward = TopoDS.Face(face.Oriented(TopAbs_FORWARD))
    pcurves = []
    edges = indexed_map(face, TopAbs_EDGE)
    for k in range(1, edges.Size() + 1):
        edge = TopoDS.Edge(edges.FindKey(k))
        # A seam carries two pcurves on the face (forward's first, as UpdateEdge takes them).
        seam = _is_seam(face, edge)
        orientations = [TopAbs_FORWARD, TopAbs_REVERSED] if seam else [edge.Orientation()]
        moved = []
        for orientation in orientations:
            curve = BRep_Tool.CurveOnSurface_s(TopoDS.Edge(edge.Oriented(orientation)), forward, 0.0, 0.0)
            if curve is None:
                return
            curve = curve.Copy()
            curve.Translate(gp_Vec2d(-du, -dv))
            moved.append(curve)
        pcurves.append((edge, moved))
    builder = BRep_Builder()
    builder.UpdateFace(face, surface, location, BRep_Tool.Tolerance_s(face))
    for edge, moved in pcurves:
        tolerance = BRep_Tool.Tolerance_s(edge)
        if len(moved) == 2:
            builder.UpdateEdge(edge, moved[0], moved[1], surface, location, tolerance)
        else:
            builder.UpdateEdge(edge, moved[0], surface, location, tolerance)
    BRepTools.Clean_s(face)


def _is_seam(face: TopoDS_Face, edge: TopoDS_Shape) -> bool:
    """The face holds `edge` both ways (its seam). An edge between two faces on one surface is closed on that
    surface too (BRep_Tool.IsClosed), but each face holds it once and gets its own pcurve."""
    orientations = set()
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        if explorer.Current().IsSame(edge):
            orientations.add(explorer.Current().Orientation())
        explorer.Next()
    return len(orientations) == 2
