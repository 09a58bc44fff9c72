"""`fuse`: patches split at their mutual intersections (BOPAlgo_Builder, non-destructive) so crossing patches
share their crossing edges; each face of the result traced back to its patch through the builder's history."""

from typing import Any

from OCP.BOPAlgo import BOPAlgo_Builder
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeVertex
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Line, GeomAbs_Plane
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_INTERNAL, TopAbs_VERTEX
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Edge, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Dir, gp_Pnt, gp_Vec

from ..constants import PARALLEL_LINES
from ..geom.booleans import arguments, check_area_kept, general_fuse, split, within
from ..geom.topology import IndexedShapeMap, ancestors, diagonal, indexed_map, subshapes
from ..protocol.errors import KernelError
from .fused_graph import describe


def fuse(
    patches: list[TopoDS_Shape],
    fuzzy: float,
    split_internal: bool = False,
    bodies: list[int] | None = None,
    patches_fused: bool = False,
    settled: set[int] | None = None,
) -> tuple[TopoDS_Shape, dict[str, Any]]:
    """(F, the reply's `faces` and `edges`). `bodies` (one per patch, optional): patches of different bodies are
    fused apart and F holds the faces of every body's fuse, so that bodies that only touch never share an edge
    (nor split each other where they overlap). `patches_fused`: each patch comes out of a fuse (its faces share
    their edges); `settled` (patch indices): patches taken unchanged from one earlier fuse (`_fuse_faces`).
    """
    how = (patches_fused, settled or set())
    groups: dict[int, list[int]] = {}
    for k, body in enumerate(bodies if bodies is not None else [0] * len(patches)):
        groups.setdefault(body, []).append(k)
    if len(groups) <= 1:
        fused, face_map, patch_of, stem_ends = _fuse_one(patches, fuzzy, split_internal, how)
        return fused, describe(fused, face_map, patch_of, stem_ends)
    fused, maker = TopoDS_Compound(), BRep_Builder()
    maker.MakeCompound(fused)
    owner: list[tuple[TopoDS_Shape, int]] = []
    stem_ends: list[TopoDS_Shape] = []
    for members in groups.values():
        part_how = (how[0], {i for i, k in enumerate(members) if k in how[1]})
        part, part_faces, part_patch, part_ends = _fuse_one(
            [patches[k] for k in members], fuzzy, split_internal, part_how
        )
        owner.extend((part_faces.FindKey(i + 1), members[p]) for i, p in enumerate(part_patch))
        stem_ends.extend(part_ends)
        maker.Add(fused, part)
    face_map = indexed_map(fused, TopAbs_FACE)
    patch_of = [-1] * face_map.Size()
    for face, patch in owner:
        patch_of[face_map.FindIndex(face) - 1] = patch
    if -1 in patch_of:
        raise KernelError("a face of a body's fuse is missing from the whole")
    return fused, describe(fused, face_map, patch_of, stem_ends)


def _fuse_one(
    patches: list[TopoDS_Shape], fuzzy: float, split_internal: bool, how: tuple[bool, set[int]]
) -> tuple[TopoDS_Shape, IndexedShapeMap, list[int], list[TopoDS_Shape]]:
    """`fuse` of patches all of one body: (F, its faces, the patch of each, its edges made by the cuts across a
    stem's end, `_stem_end_cuts`).

    Every FACE of every patch is an argument of its own, not every patch: BOPAlgo_Builder does not
    intersect the sub-shapes of one argument with each other, so the separately offset faces of a patch
    (plane + bend + plane) would keep unshared edges, and a single argument is refused outright
    (BOPAlgo_AlertTooFewArguments); `how` says when patches are already fused (`_fuse_faces`). `split_internal`:
    faces are split along the T-joints ending inside them (_internal_edge_lines); costly, so only for the result
    of a stitching pass. A seam lists its face twice, as the two sides it joins: it is no free edge (closed faces
    are split at the seam only in make_shells).
    """
    inputs, input_patch, builder = _fuse_faces(patches, fuzzy, how)
    if builder is None:
        # Nothing to intersect (and BOPAlgo refuses fewer than 2 arguments): F holds the face, if any.
        fused, maker = TopoDS_Compound(), BRep_Builder()
        maker.MakeCompound(fused)
        if inputs.Size() == 1:
            maker.Add(fused, inputs.FindKey(1))
        patch_of = input_patch
        face_map = indexed_map(fused, TopAbs_FACE)
    else:
        fused = builder.Shape()
        face_map = indexed_map(fused, TopAbs_FACE)
        patch_of = _trace_patches(builder, inputs, input_patch, face_map)
    stem_ends: list[TopoDS_Shape] = []
    if split_internal:
        tools, cuts = _internal_edge_lines(fused, face_map, patch_of, fuzzy)
        split_fused, patch_of, stem_ends = _split_faces(fused, face_map, patch_of, tools, cuts, fuzzy)
        if split_fused is not fused:
            fused, face_map = split_fused, indexed_map(split_fused, TopAbs_FACE)
    return fused, face_map, patch_of, stem_ends


def _fuse_faces(
    patches: list[TopoDS_Shape], fuzzy: float, how: tuple[bool, set[int]]
) -> tuple[IndexedShapeMap, list[int], BOPAlgo_Builder | None]:
    """Every face of `patches` once, the index of the first patch holding each, and the builder that split them
    where they meet (None for fewer than two faces); KernelError when OCCT fails or loses area.

    `how` = (patches_fused, settled). A stitching pass fuses patches that each come out of a fuse (their faces
    share their edges): each is then one argument (`booleans.arguments`), and the settled ones, kept unchanged
    from the pass's input, are one argument together. The pass then intersects what it changed (the patches
    that grew strips) with the rest, not every face with its neighbours again, which was most of its time."""
    inputs = IndexedShapeMap()
    input_patch: list[int] = []
    for k, patch in enumerate(patches):
        explorer = TopExp_Explorer(patch, TopAbs_FACE)
        while explorer.More():
            if inputs.Add(explorer.Current()) > len(input_patch):
                input_patch.append(k)
            explorer.Next()
    if inputs.Size() < 2:
        return inputs, input_patch, None
    faces = [inputs.FindKey(i + 1) for i in range(inputs.Size())]
    patches_fused, settled = how
    groups: dict[Any, list[TopoDS_Shape]] = {}
    for i, (face, patch) in enumerate(zip(faces, input_patch)):
        key = "settled" if patch in settled else (patch if patches_fused else ("face", i))
        groups.setdefault(key, []).append(face)
    builder = general_fuse(arguments(list(groups.values())), fuzzy)
    # The patches' faces overlap only where fuzzy merges them: their pieces must cover them.
    check_area_kept(builder, faces, fuzzy)
    return inputs, input_patch, builder


def _internal_edge_lines(
    fused: TopoDS_Shape, face_map: IndexedShapeMap, patch_of: list[int], fuzzy: float
) -> tuple[list[TopoDS_Shape], list[TopoDS_Shape]]:
    """A T-joint that stops inside a face (a rib ending part way up a wall) is an INTERNAL edge of that face,
    which STEP cannot carry: the face is split along the edge's line, through to its boundary, so the joint is
    a boundary edge shared by the pieces and the stem. An arc (a boss's foot on its floor) is completed to its
    circle, which cuts a disc out of the face. Any other curve on a curved face is completed the same way, as
    the section of the face with the surface of the stem standing on it, when that surface is a plane,
    cylinder or cone (a flat rib on a freeform shell): the line and the circle are that section's simplest
    cases. Other curves stay internal (on a planar face, a section of a slanted stem's cylinder would cut a
    disc the stem's foot only touches). `fused`: the fused shape, `face_map` its faces, `patch_of` the patch of
    each. Returns (the tools, the cuts across a stem's end among them: `_stem_end_cuts`)."""
    stems = ancestors(fused, TopAbs_EDGE, TopAbs_FACE)
    tools, cuts = [], []
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        lines: list[tuple[TopoDS_Edge, gp_Dir, int]] = []
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
                tools.extend(within(BRepBuilderAPI_MakeEdge(curve.Line(), first, last).Edge(), face))
                # A tube crossing the face: two faces of one cylindrical patch on the line (a seam's face is
                # listed twice, and counts once).
                sharing = {face_map.FindIndex(other) - 1 for other in stems.FindFromKey(edge)} - {i}
                stem = {patch_of[k] for k in sharing}
                if len(stem) == 1 and len(sharing) >= 2 and all(_on_cylinder(face_map, k) for k in sharing):
                    lines.append((edge, curve.Line().Direction(), stem.pop()))
            elif curve.GetType() == GeomAbs_Circle:
                tools.extend(within(BRepBuilderAPI_MakeEdge(curve.Circle()).Edge(), face))
            elif stems.Contains(edge) and BRepAdaptor_Surface(face, False).GetType() != GeomAbs_Plane:
                tools.extend(_stem_section(face, edge, stems.FindFromKey(edge)))
        cuts.extend(_stem_end_cuts(face, lines, fuzzy))
    return tools + cuts, cuts


def _on_cylinder(face_map: IndexedShapeMap, k: int) -> bool:
    """Whether face `k` of `face_map` lies on a cylinder."""
    return BRepAdaptor_Surface(TopoDS.Face(face_map.FindKey(k + 1)), False).GetType() == GeomAbs_Cylinder


def _stem_end_cuts(
    face: TopoDS_Face, lines: list[tuple[TopoDS_Edge, gp_Dir, int]], fuzzy: float
) -> list[TopoDS_Shape]:
    """Cuts across `face` between the ends of two of its INTERNAL `lines` (edge, direction, the patch of the tube
    crossing the face there: two faces of one cylindrical patch share the line) that stand on one tube and
    stop inside the face abreast: a tube (a screw boss) crossing a wall that runs on past the tube's end (a rib
    standing above the boss). The lines, extended, part off the wall's stretch inside the tube; the cut parts that
    stretch again where the tube ends, so the wall's mid-surface inside the tube's wall, below the tube's end, is
    a piece of its own, which trimming judges as an overshoot past the tube, while the stretch beyond the end
    runs on as the wall's. Only a tube: two lines of a planar stem (a U-shaped boss against a wall, a box's walls
    crossing a face) hold the wall between them, not inside the stem's wall. Abreast: the cut is square to both
    lines, within `fuzzy`."""
    if len(lines) < 2:
        return []
    ends: list[tuple[gp_Pnt, gp_Dir, int]] = []
    vertex_edges = ancestors(face, TopAbs_VERTEX, TopAbs_EDGE)
    for edge, direction, stem in lines:
        for vertex in subshapes(edge, TopAbs_VERTEX):
            # An end inside the face: no other edge of the face comes to it.
            if all(other.IsSame(edge) for other in vertex_edges.FindFromKey(vertex)):
                ends.append((BRep_Tool.Pnt_s(TopoDS.Vertex(vertex)), direction, stem))
    cuts: list[TopoDS_Shape] = []
    for k, (start, direction, stem) in enumerate(ends):
        for end, other, other_stem in ends[k + 1 :]:
            across = gp_Vec(start, end)
            if (
                other_stem != stem
                or not direction.IsParallel(other, PARALLEL_LINES)
                or across.Magnitude() <= fuzzy
                or abs(across.Dot(gp_Vec(direction))) > fuzzy
            ):
                continue
            cuts.extend(within(BRepBuilderAPI_MakeEdge(start, end).Edge(), face))
    return cuts


def _stem_section(face: TopoDS_Face, edge: TopoDS_Edge, sharing: Any) -> list[TopoDS_Shape]:
    """The edges where the surface of the first face other than `face` among `sharing` (the faces on the
    INTERNAL `edge` of `face`: the stem of the joint) crosses `face`, when that surface is a plane, cylinder or
    cone (unbounded: the section runs through to the face's boundary); [] otherwise or when OCCT gives up.
    Only the chain of section edges through `edge` is kept: the stem's surface may cross the face elsewhere too
    (a plane cuts a cylinder twice), where no stem stands, and a cut there would leave pieces hanging."""
    for other in sharing:
        if other.IsSame(face):
            continue
        if BRepAdaptor_Surface(TopoDS.Face(other), False).GetType() not in (GeomAbs_Plane, GeomAbs_Cylinder, GeomAbs_Cone):
            return []
        section = BRepAlgoAPI_Section(face, BRep_Tool.Surface_s(TopoDS.Face(other)), False)
        section.Approximation(True)
        section.Build()
        if not section.IsDone():
            return []
        return _chain_through(section.Shape(), edge)
    return []


def _chain_through(section: TopoDS_Shape, edge: TopoDS_Edge) -> list[TopoDS_Shape]:
    """The edges of `section` connected (through shared vertices) to the one nearest the middle of `edge`."""
    edges = indexed_map(section, TopAbs_EDGE)
    if edges.Size() == 0:
        return []
    curve = BRepAdaptor_Curve(edge)
    middle = BRepBuilderAPI_MakeVertex(curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter()))).Vertex()
    distances = [BRepExtrema_DistShapeShape(middle, edges.FindKey(k + 1)) for k in range(edges.Size())]
    seed = min(range(edges.Size()), key=lambda k: distances[k].Value() if distances[k].IsDone() else float("inf"))
    sharing = ancestors(section, TopAbs_VERTEX, TopAbs_EDGE)
    chain, todo = {seed}, [seed]
    while todo:
        current = edges.FindKey(todo.pop() + 1)
        for vertex in subshapes(current, TopAbs_VERTEX):
            for neighbour in sharing.FindFromKey(vertex):
                k = edges.FindIndex(neighbour) - 1
                if k >= 0 and k not in chain:
                    chain.add(k)
                    todo.append(k)
    return [edges.FindKey(k + 1) for k in sorted(chain)]


def _split_faces(
    fused: TopoDS_Shape,
    face_map: IndexedShapeMap,
    patch_of: list[int],
    tools: list[TopoDS_Shape],
    marked: list[TopoDS_Shape],
    fuzzy: float,
) -> tuple[TopoDS_Shape, list[int], list[TopoDS_Shape]]:
    """`fused` (its faces `face_map`) split by the edges `tools` lying on its faces, each piece keeping its face's
    patch, with the edges the `marked` tools became; `fused` itself (and no edges) when there are no tools, or
    OCCT gives up or breaks a face (no worse than before)."""
    if not tools:
        return fused, patch_of, []
    splitter = split(fused, tools, fuzzy, keep_area=True)
    if splitter is None:
        return fused, patch_of, []
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
        return fused, patch_of, []
    # Keep only the faces: the tools' edges outside every face would otherwise ride along as loose edges.
    faces_only, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(faces_only)
    for j in range(result_map.Size()):
        builder.Add(faces_only, result_map.FindKey(j + 1))
    made = []
    for tool in marked:
        images = splitter.Modified(tool)
        made.extend(images if images.Size() else [tool])
    return faces_only, split_patch, made  # type: ignore[return-value]


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
