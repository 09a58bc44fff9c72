"""`make_shells`: shells assembled from faces of a fused shape (BRep_Builder, so shared edges stay shared and
non-manifold edges are allowed), gathered in one compound: the shape written as the mid-surface."""

from typing import Any

from OCP.BRep import BRep_Builder
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_VERTEX
from OCP.TopoDS import TopoDS_Compound, TopoDS_Shape, TopoDS_Shell

from .errors import KernelError
from .patch_fuse import closing_isolines, split
from .topology import IndexedShapeMap, indexed_map


def make_shells(
    face_map: IndexedShapeMap, shells: list[list[int]], fuzzy: float
) -> tuple[TopoDS_Compound, dict[str, Any]]:
    """`face_map`: MapShapes(F, FACE); `shells`: valid, distinct 0-based indices into it. A face closed on
    itself is split in two at its seam first (patch_fuse.closing_isolines), fuzzy `fuzzy`.

    Returns (S, the reply's `faces` and `valid`).
    """
    images = _split_closed(face_map, [i for face_ids in shells for i in face_ids], fuzzy)
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    source: dict[int, int] = {}
    for face_ids in shells:
        shell = TopoDS_Shell()
        builder.MakeShell(shell)
        for face_id in face_ids:
            for face in images.get(face_id, [face_map.FindKey(face_id + 1)]):
                builder.Add(shell, face)
        builder.Add(compound, shell)
    own = indexed_map(compound, TopAbs_FACE)
    for face_id in [i for face_ids in shells for i in face_ids]:
        for face in images.get(face_id, [face_map.FindKey(face_id + 1)]):
            source[own.FindIndex(face) - 1] = face_id
    if len(source) != own.Size() or min(source, default=0) < 0:
        raise KernelError("a face of the shells comes from no face of the fused shape")
    return compound, {
        "faces": [source[j] for j in range(own.Size())],
        "valid": BRepCheck_Analyzer(compound).IsValid(),
        "edges": indexed_map(compound, TopAbs_EDGE).Size(),
        "vertices": indexed_map(compound, TopAbs_VERTEX).Size(),
    }


def _split_closed(face_map: IndexedShapeMap, face_ids: list[int], fuzzy: float) -> dict[int, list[TopoDS_Shape]]:
    """The pieces of each listed face closed on itself, split with all the listed faces at once so the edges
    they share are split alike; {} when none is closed or OCCT gives up (the seams stay)."""
    kept, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(kept)
    for face_id in face_ids:
        builder.Add(kept, face_map.FindKey(face_id + 1))
    tools = closing_isolines(kept)
    splitter = split(kept, tools, fuzzy) if tools else None
    if splitter is None:
        return {}
    images = {}
    for face_id in face_ids:
        modified = splitter.Modified(face_map.FindKey(face_id + 1))
        if modified.Size():
            images[face_id] = list(modified)
    # A neighbour whose shared edge was split is rebuilt too (Modified): the faces taken must be the result.
    result = indexed_map(splitter.Shape(), TopAbs_FACE)
    return images if _covers(result, images, face_map, face_ids) else {}


def _covers(
    result: IndexedShapeMap, images: dict[int, list[TopoDS_Shape]], face_map: IndexedShapeMap, face_ids: list[int]
) -> bool:
    """Whether the faces taken (images, else the face itself) are exactly the splitter's result."""
    taken = [f for i in face_ids for f in images.get(i, [face_map.FindKey(i + 1)])]
    return len(taken) == result.Size() and all(result.FindIndex(f) > 0 for f in taken)


def _source_indices(shape: TopoDS_Shape, face_map: IndexedShapeMap) -> list[int]:
    """The F-index of each face of `shape`, in MapShapes(shape, FACE) order (write_step's numbering)."""
    own = indexed_map(shape, TopAbs_FACE)
    indices = [face_map.FindIndex(own.FindKey(j + 1)) - 1 for j in range(own.Size())]
    if any(i < 0 for i in indices):
        raise KernelError("a face of the shells is not a face of the fused shape")
    return indices
