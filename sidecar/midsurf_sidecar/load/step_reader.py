"""STEP import: the solids of a file, in TopExp order, or an error naming what the file holds instead; and the
reader's problems with single entities."""

import os
import re

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Shape

from ..geom.topology import indexed_map
from ..protocol.errors import OpError
from .reanchor import reanchored


def load_step(path: str) -> list[TopoDS_Shape]:
    """Solids of the STEP file at `path`, in TopExp order; OpError with the protocol code otherwise."""
    return load_step_checked(path)[0]


def load_step_checked(path: str) -> tuple[list[TopoDS_Shape], list[dict]]:
    """`load_step`, and the reader's problems with single entities (`entity_problems`)."""
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
    problems = entity_problems(reader, path)
    # A shape broken by a corrupt entity is reported with that entity, the cause.
    first = ([p for p in problems if p["used"]] + problems)[:1]
    cause = f"; the reader failed on entity #{first[0]['entity']}: {first[0]['message']}" if first else ""
    reader.TransferRoots()
    shape = reader.OneShape()
    if reader.NbShapes() == 0 or shape.IsNull():
        raise OpError(f"holds no transferable shape, no solid{cause}", "no_solid")

    solids = indexed_map(shape, TopAbs_SOLID)
    if solids.Size() == 0:
        raise OpError(f"has {_content_summary(shape)}, no solid{cause}", "no_solid")
    return [reanchored(_placed(solids.FindKey(i))) for i in range(1, solids.Size() + 1)], problems


def _placed(solid: TopoDS_Shape) -> TopoDS_Shape:
    """The solid with its placement in the file moved into its geometry. An assembly places each part by a
    location on its solid, which every face made from it inherits, and the STEP writer's non-manifold mode does
    not always write such faces back where they were: measured, a perforated plate's mid-face (82 wires) placed
    rotated in an assembly read back with no area, failing BRepCheck; the same face with the placement in its
    geometry reads back whole. A solid placed where it was defined is returned as is."""
    if solid.Location().IsIdentity():
        return solid
    return BRepBuilderAPI_Transform(solid.Located(TopLoc_Location()), solid.Location().Transformation(), True).Shape()


# What the reader's checks say per entity, cut to this many entities (a file broken throughout says so in a
# few): enough to find them in the file.
MAX_ENTITY_PROBLEMS = 20
_DEFINITION = re.compile(rb"^\s*#(\d+)\s*=", re.MULTILINE)
_REFERENCE = re.compile(rb"#(\d+)")


def entity_problems(reader: STEPControl_Reader, path: str) -> list[dict]:
    """The reader's syntax and reference failures, per entity: its number in the file (#N), the messages, and
    whether another entity refers to it (then what it stands for, a point or a curve of the shape, is
    missing from the shape; a stray entity nothing refers to is harmless). Empty for a clean file."""
    checks = reader.WS().ModelCheckList()
    failed: list[tuple[int, list[str]]] = []
    checks.Start()
    while checks.More():
        check, number = checks.Value(), checks.Number()
        fails = [str(check.CFail(i)) for i in range(1, check.NbFails() + 1)]
        if fails:
            failed.append((number, fails))
        checks.Next()
    if not failed:
        return []
    with open(path, "rb") as f:
        text = f.read()
    data = text.find(b"DATA;")
    body = text[data:] if data >= 0 else text
    # The model numbers entities in the order the DATA section defines them.
    ids = [int(m.group(1)) for m in _DEFINITION.finditer(body)]
    referenced = {int(m.group(1)) for m in _REFERENCE.finditer(_DEFINITION.sub(b"", body))}
    # The model's own check (number 0) is the header's (a FILE_NAME field of the wrong type: no matter to the
    # shape) or repeats what the entities' checks say, without saying which: left out.
    failed = [(number, fails) for number, fails in failed if number > 0]
    if not failed:
        return []
    problems = []
    for number, fails in failed[:MAX_ENTITY_PROBLEMS]:
        entity = ids[number - 1] if 0 < number <= len(ids) else None
        problems.append({
            "entity": entity,
            "message": " ".join("; ".join(fails).split()),
            "used": entity is not None and entity in referenced,
        })
    return problems


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
