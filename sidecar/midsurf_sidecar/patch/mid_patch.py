"""`make_patch`: a mid-patch from faces of a solid, each offset along its outward normal or projected onto
a plane; the patch is a compound of the new faces in request order."""

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from OCP.BRep import BRep_Builder
from OCP.BRepTools import BRepTools, BRepTools_ReShape
from OCP.TopAbs import TopAbs_EDGE, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from ..constants import CONFUSION
from ..geom.face_measure import measure
from ..geom.solid_boundary import SolidBoundary
from ..geom.topology import IndexedShapeMap
from ..geom.vectors import Vec
from ..protocol.errors import OpError, one_line
from .face_clip import clip_to_partners, is_plane, within_solid
from .face_offset import offset_face
from .face_projection import project_face
from .mid_wall import mid_wall_face
from .wall_probe import WallProbe

# Makes the new face of the k-th requested face.
FaceMaker = Callable[[TopoDS_Face, int], TopoDS_Face]


@dataclass(frozen=True)
class Clip:
    """Partner faces per reference face (same order as the request's faces), the fuzzy tolerance, the widths
    up to which uncovered pieces stay: between covered pieces and at a dead end, and per reference face the
    faces whose footprint goes to other patches (see face_clip); the wall's thickness (None: not given), the
    step from the patch to mid-wall along the reference faces' outward normals and the thickest wall that
    pairs whatever its width, with which the clip tells a tongue lying on another wall (WallProbe)."""

    partners: list[list[int]]
    fuzzy: float
    narrow: float
    narrow_end: float
    exclude: list[list[int]]
    thickness: float | None = None
    to_mid: float = 0.0
    wall_max: float = 0.0


@dataclass(frozen=True)
class Options:
    """`clip`: see Clip; `reverse`: turn every new face over (the wall's reference side is its bottom: the
    patch normal then points out of the top side); `fill`: edges of the solid's suppressed features, whose
    inner loops are removed from the source faces before they are offset or projected; `solid`: the solid
    the faces come from, which a curved patch face is cut to (within_solid), unless what lies outside is no
    wider than `negligible`; with `cut_planes` a planar one too, when it reaches past its partners (or has
    none). An offset skin can run past where its wall's mid-plane leaves the material (a rim chamfered deeper
    than half the wall on one side); a projection onto a draft's bisector is left whole, its skins overshooting
    the rim by their draft as its neighbours' do."""

    clip: Clip | None = None
    reverse: bool = False
    fill: list[TopoDS_Shape] = field(default_factory=list)
    solid: TopoDS_Shape | None = None
    negligible: float = 0.0
    cut_planes: bool = False


def offset_patch(
    face_map: IndexedShapeMap, face_ids: list[int], distance: float, options: Options = Options()
) -> tuple[TopoDS_Compound, list, int]:
    return _patch(face_map, face_ids, lambda face, _: offset_face(face, distance), options)


def mid_wall_patch(
    face_map: IndexedShapeMap, face_ids: list[int], distance: float, options: Options
) -> tuple[TopoDS_Compound, list, int]:
    """Each face moved half-way to its clip partners point by point (a tapered wall), or by `distance` (the
    mean) where that cannot be done."""
    partners = options.clip.partners if options.clip is not None else [[] for _ in face_ids]

    def make(face: TopoDS_Face, k: int) -> TopoDS_Face:
        return mid_wall_face(face, _faces(face_map, partners[k]), distance)

    return _patch(face_map, face_ids, make, options)


def projected_patch(
    face_map: IndexedShapeMap, face_ids: list[int], origin: Vec, normal: Vec, options: Options = Options()
) -> tuple[TopoDS_Compound, list, int]:
    return _patch(face_map, face_ids, lambda face, _: project_face(face, origin, normal), options)


def _faces(face_map: IndexedShapeMap, ids: list[int]) -> list[TopoDS_Face]:
    """The faces of the solid with the given 0-based ids."""
    return [TopoDS.Face(face_map.FindKey(i + 1)) for i in ids]


def fill_loops(face: TopoDS_Face, edges: list[TopoDS_Shape]) -> tuple[TopoDS_Face, int]:
    """`face` without its inner wires that hold one of `edges` (the loops a suppressed hole or boss left), and
    how many went. The outer wire always stays."""
    outer = BRepTools.OuterWire_s(face)
    reshape = BRepTools_ReShape()
    removed = 0
    wires = TopExp_Explorer(face, TopAbs_WIRE)
    while wires.More():
        wire = wires.Current()
        wires.Next()
        if wire.IsSame(outer):
            continue
        explorer = TopExp_Explorer(wire, TopAbs_EDGE)
        while explorer.More():
            if any(explorer.Current().IsSame(e) for e in edges):
                reshape.Remove(wire)
                removed += 1
                break
            explorer.Next()
    if removed == 0:
        return face, 0
    return TopoDS.Face(reshape.Apply(face)), removed


def _patch(
    face_map: IndexedShapeMap, face_ids: list[int], make: FaceMaker, options: Options
) -> tuple[TopoDS_Compound, list[dict[str, Any]], int]:
    """(compound of the new faces, the reply's `faces`: one entry per face made, several per source face when
    a clip splits it, inner loops filled); OpError `patch_failed` naming the face."""
    clip = options.clip
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    described = []
    filled = 0
    solid = SolidBoundary(options.solid) if options.solid is not None else None
    wall = None
    if clip is not None and clip.thickness is not None and solid is not None:
        wall = WallProbe(solid, clip.thickness, clip.to_mid, clip.wall_max)
    for k, face_id in enumerate(face_ids):
        try:
            source = TopoDS.Face(face_map.FindKey(face_id + 1))
            if options.fill:
                source, removed = fill_loops(source, options.fill)
                filled += removed
            new_faces = [make(source, k)]
            overhang = True
            if clip is not None and clip.partners[k]:
                partners = _faces(face_map, clip.partners[k])
                exclude = _faces(face_map, clip.exclude[k])
                new_faces, overhang = clip_to_partners(
                    new_faces[0], partners, clip.fuzzy, clip.narrow, clip.narrow_end, exclude, wall
                )
            # A planar face over its partners' footprint lies between the wall's skins; the clip keeps narrow
            # pieces beyond it (a corner's overshoot), and what of them runs out of the solid goes here. A
            # cylinder's clip to its partners' sectors is about the axis only: a curved face is always cut.
            if solid is not None and ((options.cut_planes and overhang) or not is_plane(new_faces[0])):
                fuzzy = clip.fuzzy if clip is not None else CONFUSION
                skins = [face_id, *(clip.partners[k] if clip is not None else [])]
                skins = [face_map.FindKey(f + 1) for f in skins]
                new_faces = [
                    piece for f in new_faces for piece in within_solid(f, solid, fuzzy, options.negligible, skins)
                ]
            if options.reverse:
                new_faces = [TopoDS.Face(f.Reversed()) for f in new_faces]
            described.extend({"source": face_id, **measure(f)} for f in new_faces)
        except Exception as exc:  # OpError from our checks, Standard_Failure from OCCT
            raise OpError(f"face {face_id}: {one_line(exc)}", "patch_failed") from exc
        for f in new_faces:
            builder.Add(compound, f)
    return compound, described, filled
