"""Offset surfaces turned into B-spline surfaces before writing.

The mid-patch of a freeform face is a Geom_OffsetSurface in OCCT. That type is out of scope of the STEP schema
written (AP214), and OCCT's own reader often cannot rebuild it: the face is dropped on reading and its shell reads
back empty. The stages before writing keep the offset surfaces (booleans on them are fast and exact); the file
gets B-spline surfaces fitted to them, which every reader takes.
"""

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepTools import BRepTools_Modifier
from OCP.GeomAbs import GeomAbs_OffsetSurface
from OCP.ShapeCustom import ShapeCustom_ConvertToBSpline
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Shape

from ..geom.topology import indexed_map


def any_offset_surface(shape: TopoDS_Shape, faces: list[int]) -> bool:
    """Whether any of `faces` (MapShapes order of `shape`) lies on an offset surface."""
    face_map = indexed_map(shape, TopAbs_FACE)
    return any(_is_offset(TopoDS.Face(face_map.FindKey(j + 1))) for j in faces)


def _is_offset(face: TopoDS_Shape) -> bool:
    return BRepAdaptor_Surface(face, False).GetType() == GeomAbs_OffsetSurface


def without_offset_surfaces(shape: TopoDS_Shape) -> TopoDS_Shape:
    """`shape` with every offset surface turned into a B-spline surface, its faces in the same MapShapes order
    and its edges shared as before; `shape` itself when it has no offset surface or the conversion changes the
    faces' order or count (the names and thicknesses are attached by that order)."""
    faces = indexed_map(shape, TopAbs_FACE)
    own = [TopoDS.Face(faces.FindKey(j + 1)) for j in range(faces.Size())]
    if not any(_is_offset(face) for face in own):
        return shape
    convert = ShapeCustom_ConvertToBSpline()
    convert.SetOffsetMode(True)
    convert.SetExtrusionMode(False)
    convert.SetRevolutionMode(False)
    convert.SetPlaneMode(False)
    modifier = BRepTools_Modifier(shape, convert)
    if not modifier.IsDone():
        return shape
    converted = modifier.ModifiedShape(shape)
    new = indexed_map(converted, TopAbs_FACE)
    if new.Size() != len(own):
        return shape
    if any(not modifier.ModifiedShape(face).IsSame(new.FindKey(j + 1)) for j, face in enumerate(own)):
        return shape
    return converted
