"""The OCCT boolean calls several stages share, each with the settings every caller needs: a shape split by
tools, faces fused where they meet, an edge clipped to a face, a patch's faces merged where they lie on one
surface."""

import os

from OCP.BOPAlgo import BOPAlgo_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_BuilderAlgo, BRepAlgoAPI_Common, BRepAlgoAPI_Splitter
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.collections import List_TopoDS_Shape
from OCP.Message import Message_Fail
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Shape

from ..constants import AREA_KEPT_SHARE, CONFUSION, SAME_DOMAIN_ANGLE
from ..protocol.errors import KernelError, one_line
from .pole_offset import on_pole_offset
from .topology import boundary_length, compound_of, face_props, full_turns, indexed_map, subshapes

# MIDSURF_SERIAL_BOOLEANS=1 runs every boolean on one thread.
SERIAL_VAR = "MIDSURF_SERIAL_BOOLEANS"


def split(
    shape: TopoDS_Shape, tools: list[TopoDS_Shape], fuzzy: float, keep_area: bool = False
) -> BRepAlgoAPI_Splitter | None:
    """`shape` split by `tools` (non-destructive, fuzzy); None when OCCT gives up, or with `keep_area` when the
    pieces do not cover the faces (check_area_kept)."""
    splitter = BRepAlgoAPI_Splitter()
    arguments, tool_list = List_TopoDS_Shape(), List_TopoDS_Shape()
    arguments.Append(shape)
    for tool in tools:
        tool_list.Append(tool)
    splitter.SetArguments(arguments)
    splitter.SetTools(tool_list)
    splitter.SetFuzzyValue(fuzzy)
    splitter.SetNonDestructive(True)
    splitter.SetRunParallel(_threaded([shape, *tools]))
    splitter.Build()
    if not splitter.IsDone():
        return None
    if keep_area:
        try:
            check_area_kept(splitter, subshapes(shape, TopAbs_FACE), fuzzy)
        except KernelError:
            return None
    return splitter


def _threaded(shapes: list[TopoDS_Shape]) -> bool:
    """Whether a boolean on `shapes` runs on threads: ~1.7x faster on 2 cores (a split of 593 faces by 529 tools
    21 -> 12 s), the result (and its face and edge order) the same as a serial run. Faces on an offset of a
    freeform surface with a pole run serial (pole_offset). Should the threads crash OCCT all the same, midsurf
    runs the part again with SERIAL_VAR set."""
    return os.environ.get(SERIAL_VAR) != "1" and not any(map(on_pole_offset, shapes))


def general_fuse(shapes: list[TopoDS_Shape], fuzzy: float) -> BOPAlgo_Builder:
    """The shapes split where they meet, with the builder kept for its history. Each is one argument: a face, or
    a compound of faces already split against each other and sharing their edges, since BOPAlgo_Builder does not
    intersect the sub-shapes of one argument with each other (see `arguments`)."""
    builder = BOPAlgo_Builder()
    faces = []
    for shape in shapes:
        builder.AddArgument(shape)
        faces.extend(subshapes(shape, TopAbs_FACE))
    builder.SetFuzzyValue(fuzzy)
    builder.SetNonDestructive(True)
    builder.SetRunParallel(_threaded(faces))
    builder.Perform()
    if builder.HasErrors():
        raise KernelError(f"BOPAlgo_Builder failed on {len(faces)} faces: {_alerts(builder)}")
    return builder


def arguments(groups: list[list[TopoDS_Shape]]) -> list[TopoDS_Shape]:
    """The arguments of a general fuse: a face for a group of one, a compound for a larger group (faces already
    split against each other, which the fuse does not intersect again: the intersections of an unchanged
    neighbourhood are the bulk of a fuse's time and a place OCCT fails). Every face its own argument when that
    gives fewer than two arguments (BOPAlgo refuses one)."""
    groups = [group for group in groups if group]
    if len(groups) < 2:
        return [face for group in groups for face in group]
    return [group[0] if len(group) == 1 else compound_of(group) for group in groups]


def check_area_kept(builder: BRepAlgoAPI_BuilderAlgo | BOPAlgo_Builder, faces: list[TopoDS_Shape], fuzzy: float) -> None:
    """Raises KernelError when the images of `faces` (their pieces in `builder`'s result) do not cover their area:
    OCCT at times returns a split with loops inverted or faces dropped and no error, and patches built on that
    lose material the later stages cannot see. Each face may differ from its pieces by what merging within the
    fuzzy value moves (fuzzy x its boundary); beyond that, the faces together by AREA_KEPT_SHARE of their area."""
    total, excess, worst = 0.0, 0.0, (0.0, -1, 0.0, 0.0)
    for k, face in enumerate(faces):
        area = face_props(face).Mass()
        total += abs(area)
        images = builder.Modified(face)
        if images.Size() == 0 and not builder.IsDeleted(face):
            continue
        pieces = sum(face_props(image).Mass() for image in images)
        beyond = abs(pieces - area) - fuzzy * boundary_length(face)
        if beyond > 0.0:
            excess += beyond
            worst = max(worst, (beyond, k, pieces, area))
    if excess > AREA_KEPT_SHARE * total:
        _, k, pieces, area = worst
        raise KernelError(
            f"a split of {len(faces)} faces lost {excess:.3f} of {total:.3f} mm2 (face {k}: pieces cover {pieces:.3f} of {area:.3f})"
        )


def within(edge: TopoDS_Shape, face: TopoDS_Shape) -> list[TopoDS_Shape]:
    """The pieces of `edge` inside `face`. A tool for one face is clipped to it: a line through the whole result
    would also cut other faces of the same surface, leaving slivers the fuzzy value folds (found on
    fwdesktop_top_cover)."""
    clipped = BRepAlgoAPI_Common(edge, face)
    if not clipped.IsDone():
        return []
    pieces = indexed_map(clipped.Shape(), TopAbs_EDGE)
    return [pieces.FindKey(k + 1) for k in range(pieces.Size())]


def unify(faces: list[TopoDS_Shape], fuzzy: float) -> TopoDS_Shape:
    """One patch's faces (its kept pieces, the strips grown from its edges and the corners between them) joined
    where they touch and merged where they lie on one surface, so a strip is not left as a sliver face of its
    own. UnifySameDomain edits the shape it is given (it re-fits pcurves on periodic surfaces), and the joined
    faces include the very faces of the stitched patches that touch nothing (the fuse keeps those as they are):
    it gets a copy. When a merged face comes out broken (BRepCheck fails, or its wires turn inside out and its
    area negative), or when it goes all the way round its surface though none of the faces did, the faces are only
    joined: a broken face makes every later fuse of the part fail, losing all the joints of a stitching pass. The
    kept pieces, though they come from one fuse, are intersected with each other again, each its own argument:
    as one argument, the open length a part was left with moved by up to 6% with the mere order of the
    arguments, and a later fuse of another part lost area and failed its pass."""
    joined = general_fuse(faces, fuzzy).Shape()
    merger = ShapeUpgrade_UnifySameDomain(BRepBuilderAPI_Copy(joined, False, False).Shape(), True, True, False)
    merger.SetLinearTolerance(max(fuzzy, CONFUSION))
    merger.SetAngularTolerance(SAME_DOMAIN_ANGLE)
    merger.Build()
    merged = merger.Shape()
    # A ring made of pieces that were none (a tube's arc and the band closing its gap, a foot grown into a floor
    # with the band under the gap) came out of the next fuse broken; a tube that was whole merges as before.
    made = subshapes(merged, TopAbs_FACE)
    new_ring = any(_goes_round(f) for f in made) and not any(_goes_round(f) for f in faces)
    sound = not new_ring and all(_sound(face) for face in made)
    return merged if sound else joined


def _goes_round(face: TopoDS_Shape) -> bool:
    return any(full_turns(TopoDS.Face(face)))


def _sound(face: TopoDS_Shape) -> bool:
    """A face BRepCheck passes, with a positive area."""
    return face_props(face).Mass() > 0.0 and BRepCheck_Analyzer(face).IsValid()


def _alerts(builder: BOPAlgo_Builder) -> str:
    """The builder's failure alerts, e.g. "BOPAlgo_AlertTooFewArguments"."""
    try:
        keys = [alert.GetMessageKey() for alert in builder.GetReport().GetAlerts(Message_Fail)]
    except Exception as exc:  # the report is only for the message: never hide the failure itself
        return f"(alerts unreadable: {one_line(exc)})"
    return ", ".join(keys) or "no alert recorded"
