"""Faces of one merge set that lie on one cylinder or cone laid on a single copy of that surface whose seam runs
outside them all.

Each piece of a tube's mid-surface comes out of the fuse on a surface of its own: the offset's, or a strip's,
each with its seam (u = 0) where its frame happens to put it, some with the axis the other way. UnifySameDomain
gives up merging pieces across the seam of the surface it merges them on: a boss's mid-cylinder crossed by a rib
stays in slivers beside each arc (the pieces inside the rib, between the rib's mid-plane and the skin's edge),
faces a mesher must respect and that the thickness measured on them no longer describes. Laid on one surface
turned about its axis so that its seam falls in the widest gap between the pieces, they merge like pieces of a
plane. Only the pcurves change: every edge stays the edge it was (shared with the faces beside it), with a
pcurve added for the new surface."""

import math
from typing import Callable, NamedTuple

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_ConicalSurface, Geom_CylindricalSurface, Geom_Surface
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Cylinder
from OCP.gp import gp_Ax1, gp_Ax3, gp_Cone, gp_Cylinder, gp_Lin, gp_Vec
from OCP.ShapeAnalysis import ShapeAnalysis_Edge
from OCP.ShapeFix import ShapeFix_Edge
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FORWARD
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from ..constants import SAME_DOMAIN_ANGLE
from ..geom.face_normals import OutwardNormals
from ..geom.topology import face_props, face_wires, subshapes
from ..geom.vectors import Vec, dot

# The least gap between the pieces (radians) the seam is moved into: a narrower one leaves the seam on an edge.
LEAST_GAP = 1e-3
# How far the new face's area may differ from the piece's (relative): the same boundary on the same surface.
AREA_MATCH = 1e-6


def on_cylinder(face: TopoDS_Face, cylinder: gp_Cylinder, tolerance: float) -> bool:
    """Whether `face` lies on `cylinder` (a cylinder of the same axis and radius within `tolerance`, whatever its
    frame)."""
    adaptor = BRepAdaptor_Surface(face, False)
    if adaptor.GetType() != GeomAbs_Cylinder:
        return False
    other = adaptor.Cylinder()
    return abs(other.Radius() - cylinder.Radius()) <= tolerance and _coaxial(cylinder.Axis(), other.Axis(), tolerance)


def _on_cone(face: TopoDS_Face, cone: gp_Cone, tolerance: float) -> bool:
    """Whether `face` lies on `cone` (the same axis, apex and half-angle within `tolerance`)."""
    adaptor = BRepAdaptor_Surface(face, False)
    if adaptor.GetType() != GeomAbs_Cone:
        return False
    other = adaptor.Cone()
    return (
        abs(abs(other.SemiAngle()) - abs(cone.SemiAngle())) <= SAME_DOMAIN_ANGLE
        and other.Apex().Distance(cone.Apex()) <= tolerance
        and _coaxial(cone.Axis(), other.Axis(), tolerance)
    )


def _coaxial(axis: gp_Ax1, other: gp_Ax1, tolerance: float) -> bool:
    return axis.IsParallel(other, SAME_DOMAIN_ANGLE) and gp_Lin(axis).Distance(other.Location()) <= tolerance


class _Revolved(NamedTuple):
    """The cylinder or cone a face lies on: its frame, which faces lie on it too, and the same surface from
    another frame about the same axis."""

    frame: gp_Ax3
    holds: Callable[[TopoDS_Face], bool]
    turned_to: Callable[[gp_Ax3], Geom_Surface]


def _revolved(face: TopoDS_Face, tolerance: float) -> _Revolved | None:
    adaptor = BRepAdaptor_Surface(face, False)
    if adaptor.GetType() == GeomAbs_Cylinder:
        cylinder = adaptor.Cylinder()
        return _Revolved(
            cylinder.Position(),
            lambda f: on_cylinder(f, cylinder, tolerance),
            lambda frame: Geom_CylindricalSurface(frame, cylinder.Radius()),
        )
    if adaptor.GetType() == GeomAbs_Cone:
        cone = adaptor.Cone()
        return _Revolved(
            cone.Position(),
            lambda f: _on_cone(f, cone, tolerance),
            lambda frame: Geom_ConicalSurface(frame, cone.SemiAngle(), cone.RefRadius()),
        )
    return None


def reseat_set(faces: list[TopoDS_Shape], tolerance: float) -> list[TopoDS_Shape] | None:
    """A merge set's `faces`: those that lie on one cylinder or cone (two or more) laid on one copy of it whose
    seam lies in the widest gap between them (`_reseat`), the others as they are, in the same order; None when
    none was."""
    out, changed = list(faces), False
    todo = list(range(len(faces)))
    while todo:
        surface = _revolved(TopoDS.Face(faces[todo[0]]), tolerance)
        same = [k for k in todo if surface.holds(TopoDS.Face(faces[k]))] if surface else todo[:1]
        todo = [k for k in todo if k not in same]
        laid = _reseat([TopoDS.Face(faces[k]) for k in same], surface) if surface and len(same) > 1 else None
        if laid is not None:
            changed = True
            for k, face in zip(same, laid):
                out[k] = face
    return out if changed else None


def _reseat(faces: list[TopoDS_Face], surface: _Revolved) -> list[TopoDS_Shape] | None:
    """`faces`, all on `surface`, laid on one copy of it turned so that its seam lies in the widest gap between
    them, in the same order and orientation; None when they already share one frame whose seam lies outside them,
    when they go all the way round (no gap for the seam), or when a face cannot be laid anew exactly (its area or
    its check would change)."""
    spans = [_span(f, surface.frame) for f in faces]
    seam = _widest_gap(spans)
    if seam is None:
        return None
    if all(_same_frame(f, surface.frame) for f in faces) and not any(_crosses_zero(*span) for span in spans):
        return None
    turned = surface.turned_to(_turned(surface.frame, seam))
    laid = [_laid(f, turned) for f in faces]
    return None if any(f is None for f in laid) else laid


def _position(face: TopoDS_Face) -> gp_Ax3:
    own = BRepAdaptor_Surface(face, False)
    return own.Cylinder().Position() if own.GetType() == GeomAbs_Cylinder else own.Cone().Position()


def _same_frame(face: TopoDS_Face, frame: gp_Ax3) -> bool:
    own = _position(face)
    return (
        own.Location().IsEqual(frame.Location(), 0.0)
        and own.Direction().IsEqual(frame.Direction(), 0.0)
        and own.XDirection().IsEqual(frame.XDirection(), 0.0)
    )


def _span(face: TopoDS_Face, frame: gp_Ax3) -> tuple[float, float]:
    """Where `face` runs about `frame`'s axis: the angle it starts at, from the frame's x direction in the
    frame's turn, and how far it runs; from its u bounds on its own surface."""
    umin, umax, _, _ = BRepTools.UVBounds_s(face)
    position = _position(face)
    x, y, z = (gp_Vec(d) for d in (frame.XDirection(), frame.YDirection(), frame.Direction()))
    own_x = gp_Vec(position.XDirection())
    start = math.atan2(own_x.Dot(y), own_x.Dot(x))
    # u turns from the own frame's x towards its y: with the reference frame's turn, or against it.
    turn = gp_Vec(position.XDirection()).Crossed(gp_Vec(position.YDirection())).Dot(z)
    if turn >= 0.0:
        return start + umin, umax - umin
    return start - umax, umax - umin


def _crosses_zero(start: float, length: float) -> bool:
    """Whether the span (start, length) runs over the angle 0 of its frame."""
    a = start % (2.0 * math.pi)
    return a + length > 2.0 * math.pi - LEAST_GAP and a > LEAST_GAP


def _widest_gap(spans: list[tuple[float, float]]) -> float | None:
    """The angle in the middle of the widest stretch no span covers; None when the spans go all the way round or
    leave no gap of LEAST_GAP."""
    if any(length >= 2.0 * math.pi - LEAST_GAP for _, length in spans):
        return None
    intervals = sorted((start % (2.0 * math.pi), length) for start, length in spans)
    best, middle = 0.0, None
    # Sweep once round from the first start, then on into the next turn to close the circle.
    reach = intervals[0][0] + intervals[0][1]
    for start, length in intervals[1:] + [(intervals[0][0] + 2.0 * math.pi, 0.0)]:
        if start - reach > best:
            best, middle = start - reach, 0.5 * (start + reach)
        reach = max(reach, start + length)
    return middle if best >= LEAST_GAP else None


def _turned(frame: gp_Ax3, angle: float) -> gp_Ax3:
    """`frame` turned about its own axis by `angle`: the same surface, its seam moved there."""
    return frame.Rotated(gp_Ax1(frame.Location(), frame.Direction()), angle)


def _laid(face: TopoDS_Face, surface: Geom_Surface) -> TopoDS_Face | None:
    """`face`'s boundary (its very edges, each given a pcurve on `surface`) bounding a face of `surface`, oriented
    as `face`; None when that face's area or check differs from `face`'s."""
    wires = face_wires(TopoDS.Face(face.Oriented(TopAbs_FORWARD)))
    if not wires:
        return None
    area = abs(face_props(face).Mass())
    # The wires run round the face one way about its own surface's normal; the new surface's may be the other
    # way (a frame turned the other way round the axis): then they bound the face run backwards.
    for backwards in (False, True):
        made = _bounded(surface, [TopoDS.Wire(w.Reversed()) if backwards else w for w in wires])
        if made is not None and abs(face_props(made).Mass() - area) <= AREA_MATCH * area:
            break
    else:
        return None
    if not BRepCheck_Analyzer(made).IsValid():
        return None
    normals = [_middle_normal(f) for f in (made, face)]
    if None in normals:
        return None
    return TopoDS.Face(made.Reversed()) if dot(*normals) < 0.0 else made


def _bounded(surface: Geom_Surface, wires: list[TopoDS_Shape]) -> TopoDS_Face | None:
    """The face of `surface` bounded by `wires` (outer first), its edges given pcurves on `surface`."""
    maker = BRepBuilderAPI_MakeFace(surface, TopoDS.Wire(wires[0]), False)
    for wire in wires[1:]:
        maker.Add(TopoDS.Wire(wire))
    if not maker.IsDone():
        return None
    made = maker.Face()
    # An edge two of the faces share has its pcurve on the surface from the first.
    fixer, analysis = ShapeFix_Edge(), ShapeAnalysis_Edge()
    for edge in subshapes(made, TopAbs_EDGE):
        edge = TopoDS.Edge(edge)
        if not analysis.HasPCurve(edge, made) and not fixer.FixAddPCurve(edge, made, False):
            return None
    return made


def _middle_normal(face: TopoDS_Face) -> Vec | None:
    """The outward normal of `face` in the middle of its parameter box: the same point of the surface for a face
    and its copy laid anew (the middle angle and height of its stretch of the tube)."""
    umin, umax, vmin, vmax = BRepTools.UVBounds_s(face)
    found = OutwardNormals(face).at(0.5 * (umin + umax), 0.5 * (vmin + vmax))
    return found[1] if found else None
