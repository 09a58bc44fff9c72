"""STEP import: the solids of a file, in TopExp order, or an error naming what the file holds instead."""

import os

from OCP.BRep import BRep_Tool
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopoDS import TopoDS_Shape

from ..geom.topology import indexed_map
from ..protocol.errors import OpError


def load_step(path: str) -> list[TopoDS_Shape]:
    """Solids of the STEP file at `path`, in TopExp order; OpError with the protocol code otherwise."""
    if not os.path.exists(path):
        raise OpError("no such file", "not_found")
    if not os.path.isfile(path):
        kind = "a directory" if os.path.isdir(path) else "not a regular file"
        raise OpError(f"is {kind}; pass the path of a .step file", "not_a_file")
    if not os.access(path, os.R_OK):
        raise OpError("cannot read: permission denied", "read_failed")

    reader = STEPControl_Reader()
    status = reader.ReadFile(path)
    # After a failed ReadFile the reader's model is unusable: even NbRootsForTransfer segfaults.
    if status != IFSelect_RetDone:
        empty = " (the file is empty)" if os.path.getsize(path) == 0 else ""
        raise OpError(
            f"not a readable STEP file{empty} (reader status {status.name}); "
            "check that it is a complete STEP (ISO 10303-21) file",
            "read_failed",
        )
    reader.TransferRoots()
    shape = reader.OneShape()
    if reader.NbShapes() == 0 or shape.IsNull():
        raise OpError("holds no transferable shape, no solid", "no_solid")

    solids = indexed_map(shape, TopAbs_SOLID)
    if solids.Size() == 0:
        raise OpError(f"has {_content_summary(shape)}, no solid", "no_solid")
    return [solids.FindKey(i) for i in range(1, solids.Size() + 1)]


def _content_summary(shape: TopoDS_Shape) -> str:
    """What a solid-less shape holds, e.g. "3 faces, 1 open shell"."""
    shells = indexed_map(shape, TopAbs_SHELL)
    closed = sum(1 for i in range(1, shells.Size() + 1) if BRep_Tool.IsClosed_s(shells.FindKey(i)))
    faces = indexed_map(shape, TopAbs_FACE).Size()
    counts = [(faces, "face"), (shells.Size() - closed, "open shell"), (closed, "closed shell")]
    if faces == 0:
        # A wireframe: say what little it holds.
        counts += [
            (indexed_map(shape, TopAbs_EDGE).Size(), "edge"),
            (indexed_map(shape, TopAbs_VERTEX).Size(), "vertex"),
        ]
    return ", ".join(_count(n, noun) for n, noun in counts if n > 0) or "nothing"


def _count(n: int, noun: str) -> str:
    plural = "vertices" if noun == "vertex" else noun + "s"
    return f"{n} {noun if n == 1 else plural}"
