"""A planar mid-patch face clipped to the footprint of its partner faces.

The paper offsets the whole larger face of a pair. Where that face reaches past its partners (a plate under a
wall or a boss, a side wall whose partner stops at the floor), the offset lies over material of another
thickness, or over a joint that the other patch covers anyway. The part of the face that projects (along the
patch normal) onto one of its partners is kept; extend-and-stitch grows the clipped edges back to the
neighbouring patches.
"""

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_Transform
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.BRepTools import BRepTools
from OCP.BRepGProp import BRepGProp
from OCP.GeomAbs import GeomAbs_Plane
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_FACE, TopAbs_IN
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Pnt, gp_Trsf, gp_Vec

from .face_normals import OutwardNormals
from .face_point import interior_point
from .patch_fuse import split
from .patch_unify import unify
from .topology import diagonal, indexed_map, surface_props

# The clip is kept only when it removes more than this share of the face: below it the face already lies
# over its partners, and splitting its edges would only add work for the joints.
MIN_CLIPPED_SHARE = 0.01


def clip_to_partners(
    face: TopoDS_Face, partners: list[TopoDS_Face], fuzzy: float, narrow: float
) -> list[TopoDS_Face]:
    """The pieces of planar `face` over the footprint of `partners`, plus the uncovered pieces no wider than
    `narrow` (the band under a crossing wall, an overshoot at a corner: trimming and the joints deal with
    those as before); [face] when nothing worth clipping.

    Non-planar faces and partners are left alone (their footprint is not a prism).
    """
    if not partners or not _is_plane(face) or not all(_is_plane(p) for p in partners):
        return [face]
    normal = _plane_normal(face)
    reach = diagonal(face) + max(diagonal(p) for p in partners)
    prisms = [_prism(p, normal, reach) for p in partners]

    splitter = split(face, prisms, fuzzy)
    if splitter is None:
        return [face]
    # One classifier per prism, loaded once, asked once per piece.
    classifiers = [BRepClass3d_SolidClassifier(prism) for prism in prisms]
    pieces = indexed_map(splitter.Shape(), TopAbs_FACE)
    kept = []
    for i in range(1, pieces.Size() + 1):
        piece = TopoDS.Face(pieces.FindKey(i))
        point, _ = interior_point(OutwardNormals(piece), diagonal(piece))
        if any(_inside(c, point, fuzzy) for c in classifiers) or _width(piece) <= narrow:
            kept.append(piece)
    area = surface_props(face).Mass()
    kept_area = sum(surface_props(p).Mass() for p in kept)
    if not kept or kept_area >= (1.0 - MIN_CLIPPED_SHARE) * area:
        return [face]
    merged = indexed_map(unify(kept, fuzzy), TopAbs_FACE) if len(kept) > 1 else None
    if merged is None:
        return kept
    return [TopoDS.Face(merged.FindKey(i)) for i in range(1, merged.Size() + 1)]


def _width(face: TopoDS_Face) -> float:
    """Mean width of a face, 2 x area / perimeter: the width of a long band, the radius of a disc."""
    perimeter = GProp_GProps()
    BRepGProp.LinearProperties_s(face, perimeter)
    return 2.0 * surface_props(face).Mass() / max(perimeter.Mass(), 1e-12)


def _is_plane(face: TopoDS_Face) -> bool:
    return BRepAdaptor_Surface(face, True).GetType() == GeomAbs_Plane


def _plane_normal(face: TopoDS_Face) -> gp_Vec:
    return gp_Vec(BRepAdaptor_Surface(face, True).Plane().Axis().Direction())


def _prism(partner: TopoDS_Face, normal: gp_Vec, reach: float) -> TopoDS_Shape:
    """The partner within its outer wire swept along the normal from -reach to +reach: its footprint on any
    parallel plane. Its holes are left out: where a boss or a pocket interrupts the partner, the patch goes on
    (a hole through the wall is a hole of the reference face too, and stays)."""
    outline = BRepBuilderAPI_MakeFace(BRepTools.OuterWire_s(partner), True).Face()
    shift = gp_Trsf()
    shift.SetTranslation(normal.Multiplied(-reach))
    start = BRepBuilderAPI_Transform(outline, shift, True).Shape()
    return BRepPrimAPI_MakePrism(start, normal.Multiplied(2.0 * reach)).Shape()


def _inside(classifier: BRepClass3d_SolidClassifier, point, tolerance: float) -> bool:
    classifier.Perform(gp_Pnt(*point), max(tolerance, 1e-7))
    return classifier.State() == TopAbs_IN
