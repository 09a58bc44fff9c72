"""`fuse`: patches split at their mutual intersections (BOPAlgo_Builder, non-destructive) so crossing patches
share their crossing edges; each face of the result traced back to its patch through the builder's history."""

from typing import Any

from OCP.BOPAlgo import BOPAlgo_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Splitter
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Line
from OCP.collections import List_TopoDS_Shape
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.Message import Message_Fail
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_INTERNAL
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Edge, TopoDS_Shape

from .errors import KernelError, one_line
from .face_measure import measure
from .topology import diagonal, IndexedShapeMap, indexed_map
from .vectors import xyz

# Points reported along each edge, evenly spaced by parameter, both ends included.
EDGE_POINTS = 5


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


def fuse(patches: list[TopoDS_Shape], fuzzy: float, split_internal: bool = False) -> tuple[TopoDS_Shape, dict[str, Any]]:
    """(F, the reply's `faces` and `edges`).

    Every FACE of every patch is an argument of its own, not every patch: BOPAlgo_Builder does not
    intersect the sub-shapes of one argument with each other, so the separately offset faces of a patch
    (plane + bend + plane) would keep unshared edges, and a single argument is refused outright
    (BOPAlgo_AlertTooFewArguments). `split_internal`: faces are split along the T-joints ending inside them
    (_internal_edge_lines); costly, so only for the result of a stitching pass. A seam lists its face twice,
    as the two sides it joins: it is no free edge (closed faces are split at the seam only in make_shells).
    """
    # Every input face once, with the index of the first patch holding it.
    inputs = IndexedShapeMap()
    input_patch: list[int] = []
    for k, patch in enumerate(patches):
        explorer = TopExp_Explorer(patch, TopAbs_FACE)
        while explorer.More():
            if inputs.Add(explorer.Current()) > len(input_patch):
                input_patch.append(k)
            explorer.Next()
    if inputs.Size() < 2:
        # Nothing to intersect (and BOPAlgo refuses fewer than 2 arguments): F holds the face, if any.
        fused, maker = TopoDS_Compound(), BRep_Builder()
        maker.MakeCompound(fused)
        if inputs.Size() == 1:
            maker.Add(fused, inputs.FindKey(1))
        patch_of = input_patch
        face_map = indexed_map(fused, TopAbs_FACE)
    else:
        builder = general_fuse([inputs.FindKey(i + 1) for i in range(inputs.Size())], fuzzy)
        fused = builder.Shape()
        face_map = indexed_map(fused, TopAbs_FACE)
        patch_of = _trace_patches(builder, inputs, input_patch, face_map)
    if split_internal:
        split_fused, patch_of = _split_faces(fused, face_map, patch_of, _internal_edge_lines(face_map), fuzzy)
        if split_fused is not fused:
            fused, face_map = split_fused, indexed_map(split_fused, TopAbs_FACE)
    return fused, _describe(fused, face_map, patch_of)


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


def _internal_edge_lines(face_map: IndexedShapeMap) -> list[TopoDS_Shape]:
    """A T-joint that stops inside a face (a rib ending part way up a wall) is an INTERNAL edge of that face,
    which STEP cannot carry: the face is split along the edge's line, through to its boundary, so the joint is
    a boundary edge shared by the pieces and the stem. An arc (a boss's foot on its floor) is completed to its
    circle, which cuts a disc out of the face. Other curves stay internal. `face_map`: the faces of the fused
    shape."""
    tools = []
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        explorer = TopExp_Explorer(face, TopAbs_EDGE)
        while explorer.More():
            edge = TopoDS.Edge(explorer.Current())
            explorer.Next()
            if edge.Orientation() != TopAbs_INTERNAL or BRep_Tool.Degenerated_s(edge):
                continue
            curve = BRepAdaptor_Curve(edge)
            if curve.GetType() == GeomAbs_Line:
                reach = diagonal(face)
                first, last = curve.FirstParameter() - reach, curve.LastParameter() + reach
                tools.extend(_within(BRepBuilderAPI_MakeEdge(curve.Line(), first, last).Edge(), face))
            elif curve.GetType() == GeomAbs_Circle:
                tools.extend(_within(BRepBuilderAPI_MakeEdge(curve.Circle()).Edge(), face))
    return tools


# A face spanning its surface's period to within this share closes on itself (UV bounds carry float noise).
FULL_TURN = 1e-9


def closing_isolines(faces: list[TopoDS_Shape]) -> list[TopoDS_Shape]:
    """A face closed on itself (a tube's cylinder, a dome's sphere, an elbow's torus) is bounded by its seam
    twice: that edge belongs to one face only, so a mesher or a topology check (the judge) takes it for a free
    edge, a gap in the shell. Split in two along these isolines halfway round, the seam and the isoline each
    join the two halves. Only for the shells written: split before trimming, a tube's overshoot past a tee
    stayed joined to the rest of its tube along the isoline (salome_pipe)."""
    tools = []
    for shape in faces:
        face = TopoDS.Face(shape)
        surface = BRep_Tool.Surface_s(face)
        if not (surface.IsUPeriodic() or surface.IsVPeriodic()):
            continue  # most faces: no need for the UV bounds
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        isolines = []
        if surface.IsUPeriodic() and u1 - u0 >= surface.UPeriod() * (1 - FULL_TURN):
            isolines.append(BRepBuilderAPI_MakeEdge(surface.UIso((u0 + u1) / 2), v0, v1))
        if surface.IsVPeriodic() and v1 - v0 >= surface.VPeriod() * (1 - FULL_TURN):
            isolines.append(BRepBuilderAPI_MakeEdge(surface.VIso((v0 + v1) / 2), u0, u1))
        for maker in isolines:
            if maker.IsDone():
                tools.extend(_within(maker.Edge(), face))
    return tools


def _within(edge: TopoDS_Shape, face: TopoDS_Shape) -> list[TopoDS_Shape]:
    """The pieces of `edge` inside `face`. A tool for one face is clipped to it: a line through the whole result
    would also cut other faces of the same surface, leaving slivers the fuzzy value folds (found on
    fwdesktop_top_cover)."""
    clipped = BRepAlgoAPI_Common(edge, face)
    if not clipped.IsDone():
        return []
    pieces = indexed_map(clipped.Shape(), TopAbs_EDGE)
    return [pieces.FindKey(k + 1) for k in range(pieces.Size())]


def _split_faces(
    fused: TopoDS_Shape, face_map: IndexedShapeMap, patch_of: list[int], tools: list[TopoDS_Shape], fuzzy: float
) -> tuple[TopoDS_Shape, list[int]]:
    """`fused` (its faces `face_map`) split by the edges `tools` lying on its faces, each piece keeping its face's
    patch; `fused` itself when there are no tools or OCCT gives up (no worse than before)."""
    if not tools:
        return fused, patch_of
    splitter = split(fused, tools, fuzzy)
    if splitter is None:
        return fused, patch_of
    result = splitter.Shape()
    result_map = indexed_map(result, TopAbs_FACE)
    split_patch: list[int | None] = [None] * result_map.Size()
    for i in range(face_map.Size()):
        face = face_map.FindKey(i + 1)
        images = splitter.Modified(face)
        for image in images if images.Size() else [face]:
            index = result_map.FindIndex(image) - 1
            if index >= 0 and split_patch[index] is None:
                split_patch[index] = patch_of[i]
    if any(p is None for p in split_patch):
        return fused, patch_of
    # Keep only the faces: the tools' edges outside every face would otherwise ride along as loose edges.
    faces_only, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(faces_only)
    for j in range(result_map.Size()):
        builder.Add(faces_only, result_map.FindKey(j + 1))
    return faces_only, split_patch  # type: ignore[return-value]


def _describe(fused: TopoDS_Shape, face_map: IndexedShapeMap, patch_of: list[int]) -> dict[str, Any]:
    """The reply's `faces` (face_map: the faces of F; patch_of: the patch of each) and `edges`."""
    edge_map = indexed_map(fused, TopAbs_EDGE)
    edge_faces: list[list[int]] = [[] for _ in range(edge_map.Size())]
    faces = []
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        edges, seams = _face_edges(face, edge_map)
        for e in edges:
            edge_faces[e].append(i)
            if e in seams:
                edge_faces[e].append(i)  # a seam joins the face to itself
        try:
            faces.append({"patch": patch_of[i], **measure(face), "edges": edges})
        except Exception as exc:
            raise KernelError(f"fused face {i} (patch {patch_of[i]}): {one_line(exc)}") from exc
    edges_json = []
    for e in range(edge_map.Size()):
        try:
            edges_json.append(_describe_edge(TopoDS.Edge(edge_map.FindKey(e + 1)), edge_faces[e]))
        except Exception as exc:
            raise KernelError(f"fused edge {e} (faces {edge_faces[e]}): {one_line(exc)}") from exc
    return {"faces": faces, "edges": edges_json}


def _trace_patches(
    builder: BOPAlgo_Builder, inputs: IndexedShapeMap, input_patch: list[int], face_map: IndexedShapeMap
) -> list[int]:
    """The patch of each face of the result: an input face is either kept as is (no images, not
    deleted) or replaced by its images (Modified). A face claimed by two patches (fuzzy-merged overlaps)
    keeps the lower patch index."""
    patch_of: list[int | None] = [None] * face_map.Size()

    def claim(face: TopoDS_Shape, patch: int) -> None:
        index = face_map.FindIndex(face) - 1
        if index >= 0 and patch_of[index] is None:
            patch_of[index] = patch

    for i in range(inputs.Size()):
        face = inputs.FindKey(i + 1)
        images = builder.Modified(face)
        if images.Size() == 0:
            if not builder.IsDeleted(face):
                claim(face, input_patch[i])
        elif images.Size() == 1:
            claim(images.First(), input_patch[i])
        else:
            for image in images:
                claim(image, input_patch[i])
    missing = [i for i, patch in enumerate(patch_of) if patch is None]
    if missing:
        raise KernelError(f"fused faces {missing[:10]} come from no patch (BOPAlgo_Builder history)")
    return patch_of  # type: ignore[return-value]


def _face_edges(face: TopoDS_Shape, edge_map: IndexedShapeMap) -> tuple[list[int], set[int]]:
    """(edge indices of the face in explorer order, a seam once; the seams). A seam is an edge the face uses
    twice (once each way). Not BRep_Tool.IsClosed: a piece of a split tube keeps both pcurves on the old seam
    edge although it uses it once, where it is a boundary like any other."""
    uses: dict[int, int] = {}
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        e = edge_map.FindIndex(explorer.Current()) - 1
        uses[e] = uses.get(e, 0) + 1
        explorer.Next()
    return list(uses), {e for e, n in uses.items() if n > 1}


def _describe_edge(edge: TopoDS_Edge, faces: list[int]) -> dict[str, Any]:
    if BRep_Tool.Degenerated_s(edge):
        # No 3D curve: the edge is its vertex.
        point = list(xyz(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(edge))))
        return {"length": 0.0, "faces": faces, "points": [point] * EDGE_POINTS}
    curve = BRepAdaptor_Curve(edge)
    first, last = curve.FirstParameter(), curve.LastParameter()
    step = (last - first) / (EDGE_POINTS - 1)
    points = [list(xyz(curve.Value(first + k * step))) for k in range(EDGE_POINTS - 1)]
    points.append(list(xyz(curve.Value(last))))
    return {"length": GCPnts_AbscissaPoint.Length_s(curve), "faces": faces, "points": points}


def _alerts(builder: BOPAlgo_Builder) -> str:
    """The builder's failure alerts, e.g. "BOPAlgo_AlertTooFewArguments"."""
    try:
        keys = [alert.GetMessageKey() for alert in builder.GetReport().GetAlerts(Message_Fail)]
    except Exception as exc:  # the report is only for the message: never hide the failure itself
        return f"(alerts unreadable: {one_line(exc)})"
    return ", ".join(keys) or "no alert recorded"
