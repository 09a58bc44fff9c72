"""`make_patch`: a mid-patch from faces of a solid, each offset along its outward normal or projected onto
a plane; the patch is a compound of the new faces in request order."""

from collections.abc import Callable
from typing import Any

from OCP.BRep import BRep_Builder
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from .errors import OpError, one_line
from .face_measure import measure
from .face_offset import offset_face
from .face_projection import project_face
from .topology import IndexedShapeMap, indexed_map
from .vectors import Vec

FaceMaker = Callable[[TopoDS_Face], TopoDS_Face]


def offset_patch(solid: TopoDS_Shape, face_ids: list[int], distance: float) -> tuple[TopoDS_Compound, list]:
    return _patch(indexed_map(solid, TopAbs_FACE), face_ids, lambda face: offset_face(face, distance))


def projected_patch(
    solid: TopoDS_Shape, face_ids: list[int], origin: Vec, normal: Vec
) -> tuple[TopoDS_Compound, list]:
    return _patch(indexed_map(solid, TopAbs_FACE), face_ids, lambda face: project_face(face, origin, normal))


def _patch(
    face_map: IndexedShapeMap, face_ids: list[int], make: FaceMaker
) -> tuple[TopoDS_Compound, list[dict[str, Any]]]:
    """(compound of the new faces, the reply's `faces`); OpError `patch_failed` naming the face."""
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    described = []
    for face_id in face_ids:
        try:
            new_face = make(TopoDS.Face(face_map.FindKey(face_id + 1)))
            described.append({"source": face_id, **measure(new_face)})
        except Exception as exc:  # OpError from our checks, Standard_Failure from OCCT
            raise OpError(f"face {face_id}: {one_line(exc)}", "patch_failed") from exc
        builder.Add(compound, new_face)
    return compound, described
