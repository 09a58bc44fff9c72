"""Offset of one face along its outward normal (BRepOffsetAPI_MakeOffsetShape.PerformBySimple); an offset of a
freeform surface with a pole is approximated by a B-spline (geom.pole_offset.as_bspline).

An offset that reaches the axis or centre of a cylinder, cone, sphere or torus gives a degenerate face
that OCCT still reports as valid (KERNEL_NOTES), so that case is refused before OCCT is called.
"""

import math

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakeOffsetShape
from OCP.BRepTools import BRepTools
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Sphere, GeomAbs_Torus
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Face

from ..constants import COLLAPSE_RATIO
from ..describe.surface_kind import describe_surface
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import interior_point
from ..geom.pole_offset import as_bspline
from ..geom.topology import diagonal, indexed_map
from ..geom.uv_box import face_on_box, fills_its_box
from ..protocol.errors import OpError, one_line

CURVED_KINDS = (GeomAbs_Cylinder, GeomAbs_Cone, GeomAbs_Sphere, GeomAbs_Torus)


def offset_face(face: TopoDS_Face, distance: float) -> TopoDS_Face:
    """The face moved by `distance` along its outward normal (< 0: into the material).

    Raises OpError `patch_failed` (message without the face id: the caller adds it).
    """
    if distance == 0.0:
        # A patch on the face's own skin (offset position top): MakeOffsetShape would fail or copy anyway.
        return TopoDS.Face(BRepBuilderAPI_Copy(face).Shape())
    _refuse_collapse(face, distance)
    maker = BRepOffsetAPI_MakeOffsetShape()
    try:
        maker.PerformBySimple(face, distance)
    except Exception as exc:
        raise OpError(f"offset by {distance:g} failed: {one_line(exc)}", "patch_failed") from exc
    if not maker.IsDone():
        raise OpError(f"offset by {distance:g} failed (MakeOffsetShape not done)", "patch_failed")
    result = maker.Shape()
    faces = indexed_map(result, TopAbs_FACE) if not result.IsNull() else None
    if faces is None or faces.Size() != 1:
        count = 0 if faces is None else faces.Size()
        raise OpError(f"offset by {distance:g} gave {count} faces instead of 1", "patch_failed")
    return as_bspline(_cone_on_its_box(TopoDS.Face(faces.FindKey(1))))


def _cone_on_its_box(face: TopoDS_Face) -> TopoDS_Face:
    """An offset cone that is the whole box of its parameters, rebuilt on that box. OCCT's simple offset gives a
    cone's edges as approximated B-spline curves; fused with a patch it touches tangentially along one of them (a
    drafted wall running into a drafted rounded corner), that edge came out 0.016 mm off both faces, and 0.28 mm
    after the stitching's fuses. On its box, the face's edges are the cone's exact lines and circles. Any other
    face, or a cone trimmed otherwise (a hole in it, a slanted cut), is returned as it is."""
    if BRepAdaptor_Surface(face, False).GetType() != GeomAbs_Cone or not fills_its_box(face):
        return face
    return face_on_box(BRep_Tool.Surface_s(face), BRepTools.UVBounds_s(face), face) or face


def _refuse_collapse(face: TopoDS_Face, distance: float) -> None:
    adaptor = BRepAdaptor_Surface(face, True)
    kind = adaptor.GetType()
    if kind not in CURVED_KINDS or distance == 0.0:
        return
    normals = OutwardNormals(face)
    point, normal = interior_point(normals, diagonal(face))
    surface = describe_surface(adaptor, normals.reversed, point, normal)
    # Outward normal away from the axis/centre: a positive offset grows the radius.
    grow = 1.0 if surface["convex"] else -1.0
    if kind == GeomAbs_Torus:
        radius, what = surface["minor_radius"], "minor radius"
        new_radius = radius + grow * distance
    elif kind == GeomAbs_Cone:
        # The normal leans off the radial direction by the half angle; the smallest radius of the
        # face (at one end of its v range) is the first to reach the axis.
        radius, what = _smallest_cone_radius(face, adaptor), "smallest radius"
        new_radius = radius + grow * distance * math.cos(surface["half_angle"])
    else:
        radius, what = surface["radius"], "radius"
        new_radius = radius + grow * distance
    if new_radius <= COLLAPSE_RATIO * radius:
        side = "convex" if surface["convex"] else "concave"
        raise OpError(
            f"offset by {distance:g} would collapse the {surface['kind']} ({side}, {what} {radius:g}) "
            f"to radius {new_radius:g}: pair this face differently or leave it out",
            "patch_failed",
        )


def _smallest_cone_radius(face: TopoDS_Face, adaptor: BRepAdaptor_Surface) -> float:
    cone = adaptor.Cone()
    _, _, v0, v1 = BRepTools.UVBounds_s(face)
    # gp_Cone: radius(v) = RefRadius + v sin(SemiAngle); negative past the apex.
    r0, r1 = (cone.RefRadius() + v * math.sin(cone.SemiAngle()) for v in (v0, v1))
    return 0.0 if r0 * r1 <= 0.0 else min(abs(r0), abs(r1))
