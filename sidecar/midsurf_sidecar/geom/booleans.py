"""The OCCT boolean calls several stages share, each with the settings every caller needs: a shape split by
tools, faces fused where they meet, an edge clipped to a face, a patch's faces merged where they lie on one
surface."""

from OCP.BOPAlgo import BOPAlgo_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Splitter
from OCP.collections import List_TopoDS_Shape
from OCP.Message import Message_Fail
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopAbs import TopAbs_EDGE
from OCP.TopoDS import TopoDS_Shape

from ..constants import CONFUSION, SAME_DOMAIN_ANGLE
from ..protocol.errors import KernelError, one_line
from .topology import indexed_map


def split(shape: TopoDS_Shape, tools: list[TopoDS_Shape], fuzzy: float) -> BRepAlgoAPI_Splitter | None:
    """`shape` split by `tools` (non-destructive, fuzzy); None when OCCT gives up."""
    splitter = BRepAlgoAPI_Splitter()
    arguments, tool_list = List_TopoDS_Shape(), List_TopoDS_Shape()
    arguments.Append(shape)
    for tool in tools:
        tool_list.Append(tool)
    splitter.SetArguments(arguments)
    splitter.SetTools(tool_list)
    splitter.SetFuzzyValue(fuzzy)
    splitter.SetNonDestructive(True)
    splitter.Build()
    return splitter if splitter.IsDone() else None


def general_fuse(faces: list[TopoDS_Shape], fuzzy: float) -> BOPAlgo_Builder:
    """The faces split where they meet (each its own argument), with the builder kept for its history."""
    builder = BOPAlgo_Builder()
    for face in faces:
        builder.AddArgument(face)
    builder.SetFuzzyValue(fuzzy)
    builder.SetNonDestructive(True)
    # ~1.7x faster on 2 cores; the result (and its face and edge order) is the same as a serial run.
    builder.SetRunParallel(True)
    builder.Perform()
    if builder.HasErrors():
        raise KernelError(f"BOPAlgo_Builder failed on {len(faces)} faces: {_alerts(builder)}")
    return builder


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
    own."""
    merger = ShapeUpgrade_UnifySameDomain(general_fuse(faces, fuzzy).Shape(), True, True, False)
    merger.SetLinearTolerance(max(fuzzy, CONFUSION))
    merger.SetAngularTolerance(SAME_DOMAIN_ANGLE)
    merger.Build()
    return merger.Shape()


def _alerts(builder: BOPAlgo_Builder) -> str:
    """The builder's failure alerts, e.g. "BOPAlgo_AlertTooFewArguments"."""
    try:
        keys = [alert.GetMessageKey() for alert in builder.GetReport().GetAlerts(Message_Fail)]
    except Exception as exc:  # the report is only for the message: never hide the failure itself
        return f"(alerts unreadable: {one_line(exc)})"
    return ", ".join(keys) or "no alert recorded"
