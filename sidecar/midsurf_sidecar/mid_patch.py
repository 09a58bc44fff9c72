"""`make_patch`: a mid-patch from faces of a solid, each offset along its outward normal or projected onto
a plane; the patch is a compound of the new faces in request order."""

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from OCP.BRep import BRep_Builder
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from .errors import OpError, one_line
from .face_clip import clip_to_partners
from .face_measure import measure
from .face_offset import offset_face
from .face_projection import project_face
from .topology import IndexedShapeMap, indexed_map
from .vectors import Vec

FaceMaker = Callable[[TopoDS_Face], TopoDS_Face]


@dataclass(frozen=True)
class Clip:
    """Partner faces per reference face (same order as the request's faces), the fuzzy tolerance, and the
    width up to which uncovered pieces stay (see face_clip)."""

    partners: list[list[int]]
    fuzzy: float
    narrow: float


def offset_patch(
    solid: TopoDS_Shape, face_ids: list[int], distance: float, clip: Clip | None = None, reverse: bool = False
) -> tuple[TopoDS_Compound, list]:
    faces = indexed_map(solid, TopAbs_FACE)
    return _patch(faces, face_ids, lambda face: offset_face(face, distance), clip, reverse)


def projected_patch(
    solid: TopoDS_Shape, face_ids: list[int], origin: Vec, normal: Vec, clip: Clip | None = None, reverse: bool = False
) -> tuple[TopoDS_Compound, list]:
    faces = indexed_map(solid, TopAbs_FACE)
    return _patch(faces, face_ids, lambda face: project_face(face, origin, normal), clip, reverse)


def _patch(
    face_map: IndexedShapeMap, face_ids: list[int], make: FaceMaker, clip: Clip | None, reverse: bool
) -> tuple[TopoDS_Compound, list[dict[str, Any]]]:
    """(compound of the new faces, the reply's `faces`: one entry per face made, several per source face when
    a clip splits it); OpError `patch_failed` naming the face. `reverse` turns every new face over (the wall's
    reference side is its bottom: the patch normal then points out of the top side)."""
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    described = []
    for k, face_id in enumerate(face_ids):
        try:
            new_faces = [make(TopoDS.Face(face_map.FindKey(face_id + 1)))]
            if clip is not None and clip.partners[k]:
                partners = [TopoDS.Face(face_map.FindKey(p + 1)) for p in clip.partners[k]]
                new_faces = clip_to_partners(new_faces[0], partners, clip.fuzzy, clip.narrow)
            if reverse:
                new_faces = [TopoDS.Face(f.Reversed()) for f in new_faces]
            described.extend({"source": face_id, **measure(f)} for f in new_faces)
        except Exception as exc:  # OpError from our checks, Standard_Failure from OCCT
            raise OpError(f"face {face_id}: {one_line(exc)}", "patch_failed") from exc
        for f in new_faces:
            builder.Add(compound, f)
    return compound, described
