"""Faces that are the whole box of their surface's parameters (bounded by four iso-lines), and faces made on such
a box: their edges are the surface's exact iso-lines, not curves approximated by an earlier operation."""

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepTools import BRepTools
from OCP.TopoDS import TopoDS, TopoDS_Face

from ..constants import CONFUSION, RECTANGLE_SHARE
from .topology import surface_props


def face_on_box(surface, bounds: tuple[float, float, float, float], like: TopoDS_Face) -> TopoDS_Face | None:
    """The face of `surface` on the parameter box `bounds` (u0, u1, v0, v1), oriented as `like`; None when OCCT
    cannot make it or it fails BRepCheck."""
    maker = BRepBuilderAPI_MakeFace(surface, *bounds, CONFUSION)
    if not maker.IsDone() or not BRepCheck_Analyzer(maker.Face()).IsValid():
        return None
    return TopoDS.Face(maker.Face().Oriented(like.Orientation()))


def fills_its_box(face: TopoDS_Face) -> bool:
    """Whether `face` is the whole box of its parameter range: its area and that box's differ by no more than
    `RECTANGLE_SHARE` (a hole or a slanted cut makes it smaller)."""
    boxed = face_on_box(BRep_Tool.Surface_s(face), BRepTools.UVBounds_s(face), face)
    if boxed is None:
        return False
    area = surface_props(face).Mass()
    return abs(surface_props(boxed).Mass() - area) <= RECTANGLE_SHARE * area
