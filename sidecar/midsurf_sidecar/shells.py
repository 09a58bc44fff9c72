"""`make_shells`: shells assembled from faces of a fused shape (BRep_Builder, so shared edges stay shared and
non-manifold edges are allowed), gathered in one compound: the shape written as the mid-surface."""

from typing import Any

from OCP.BRep import BRep_Builder
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_VERTEX
from OCP.TopoDS import TopoDS_Compound, TopoDS_Shape, TopoDS_Shell

from .errors import KernelError
from .topology import IndexedShapeMap, indexed_map


def make_shells(face_map: IndexedShapeMap, shells: list[list[int]]) -> tuple[TopoDS_Compound, dict[str, Any]]:
    """`face_map`: MapShapes(F, FACE); `shells`: valid, distinct 0-based indices into it.

    Returns (S, the reply's `faces` and `valid`).
    """
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    for face_ids in shells:
        shell = TopoDS_Shell()
        builder.MakeShell(shell)
        for face_id in face_ids:
            builder.Add(shell, face_map.FindKey(face_id + 1))
        builder.Add(compound, shell)
    faces = _source_indices(compound, face_map)
    return compound, {
        "faces": faces,
        "valid": BRepCheck_Analyzer(compound).IsValid(),
        "edges": indexed_map(compound, TopAbs_EDGE).Size(),
        "vertices": indexed_map(compound, TopAbs_VERTEX).Size(),
    }


def _source_indices(shape: TopoDS_Shape, face_map: IndexedShapeMap) -> list[int]:
    """The F-index of each face of `shape`, in MapShapes(shape, FACE) order (write_step's numbering)."""
    own = indexed_map(shape, TopAbs_FACE)
    indices = [face_map.FindIndex(own.FindKey(j + 1)) - 1 for j in range(own.Size())]
    if any(i < 0 for i in indices):
        raise KernelError("a face of the shells is not a face of the fused shape")
    return indices
