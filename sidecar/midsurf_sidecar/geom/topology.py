"""Indexed sub-shape maps and mass properties: the id and measurement conventions shared by all ops."""

from collections.abc import Iterator

from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools
from OCP.collections import IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as AncestorMap
from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as IndexedShapeMap
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_WIRE, TopAbs_ShapeEnum
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Edge, TopoDS_Face, TopoDS_Iterator, TopoDS_Shape, TopoDS_Wire
from OCP.gp import gp_Pnt

from ..constants import FACE_PROPS_KEPT, FULL_TURN


def full_turns(face: TopoDS_Face) -> tuple[bool, bool]:
    """Whether `face` goes all the way round its surface along u, and along v (a tube's cylinder, a dome's
    sphere, an elbow's torus): closed, not only periodic (a B-spline closed on itself, as some CAD writes tubes
    and as a freeform dome's mid-patch is, has a seam too)."""
    surface = BRep_Tool.Surface_s(face)
    u_closed = surface.IsUPeriodic() or surface.IsUClosed()
    v_closed = surface.IsVPeriodic() or surface.IsVClosed()
    if not (u_closed or v_closed):
        return False, False  # most faces: no need for the UV bounds
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    su0, su1, sv0, sv1 = surface.Bounds()
    u_turn = surface.UPeriod() if surface.IsUPeriodic() else su1 - su0
    v_turn = surface.VPeriod() if surface.IsVPeriodic() else sv1 - sv0
    return u_closed and u1 - u0 >= u_turn * (1 - FULL_TURN), v_closed and v1 - v0 >= v_turn * (1 - FULL_TURN)


def compound_of(shapes: list[TopoDS_Shape]) -> TopoDS_Compound:
    """The shapes as one compound, in their order."""
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    for shape in shapes:
        builder.Add(compound, shape)
    return compound


def distance_to(point: gp_Pnt, shape: TopoDS_Shape) -> float | None:
    """The distance from `point` to `shape`; None when OCCT cannot tell."""
    distance = BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(point).Vertex(), shape)
    return distance.Value() if distance.IsDone() else None


def indexed_map(shape: TopoDS_Shape, kind: TopAbs_ShapeEnum) -> IndexedShapeMap:
    """Sub-shapes of `kind` in TopExp order; id = map index - 1, stable across re-reads of the same file."""
    shape_map = IndexedShapeMap()
    TopExp.MapShapes_s(shape, kind, shape_map)
    return shape_map


def invalid_faces(shape: TopoDS_Shape, faces: IndexedShapeMap) -> list[int] | None:
    """None when `shape` passes BRepCheck, else the ids of its `faces` (its face map) that fail it, checked face
    by face only then, so a sound shape costs one check (the list may be empty: the whole can fail alone)."""
    if BRepCheck_Analyzer(shape).IsValid():
        return None
    return [j for j in range(faces.Size()) if not BRepCheck_Analyzer(faces.FindKey(j + 1)).IsValid()]


def ancestors(shape: TopoDS_Shape, kind: TopAbs_ShapeEnum, owner: TopAbs_ShapeEnum) -> AncestorMap:
    """Each sub-shape of `kind` in `shape` (TopExp order) with the sub-shapes of kind `owner` that hold it (an
    edge's faces, a vertex's edges)."""
    found = AncestorMap()
    TopExp.MapShapesAndAncestors_s(shape, kind, owner, found)
    return found


def edge_uses(shape: TopoDS_Shape, seams_free: bool = True) -> tuple[int, int]:
    """Edges of `shape` used by one face (free) and by three or more (non-manifold), degenerate edges left out
    and a seam counted once per face: free, unless not `seams_free` (a closed face's seam joins it to itself)."""
    owners = ancestors(shape, TopAbs_EDGE, TopAbs_FACE)
    free = nonmanifold = 0
    for k in range(1, owners.Size() + 1):
        edge = TopoDS.Edge(owners.FindKey(k))
        if BRep_Tool.Degenerated_s(edge):
            continue
        faces = IndexedShapeMap()
        for face in owners.FindFromIndex(k):
            faces.Add(face)
        seam = faces.Size() == 1 and BRep_Tool.IsClosed_s(edge, TopoDS.Face(faces.FindKey(1)))
        free += faces.Size() == 1 and (seams_free or not seam)
        nonmanifold += faces.Size() >= 3
    return free, nonmanifold


def volume(shape: TopoDS_Shape) -> float:
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def surface_props(shape: TopoDS_Shape) -> GProp_GProps:
    """Area (Mass) and centroid (CentreOfMass) of the faces of `shape`."""
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props


# Per face hash, (face, its surface_props) of the faces a boolean made or took, for `face_props`.
_FACE_PROPS: dict[int, list[tuple[TopoDS_Shape, GProp_GProps]]] = {}


def face_props(face: TopoDS_Shape) -> GProp_GProps:
    """`surface_props` of a face made by, or given to, a boolean, integrated once per face (the same TShape,
    location and orientation). A stitching pass integrates the same faces several times: a fuse's check sums the
    areas of its inputs and of their pieces, its reply measures the pieces again, and the next pass's fuse takes
    most of them unchanged as inputs (12% of a slow part's time went to integrating areas, mostly again). Such
    faces are never edited in place: the booleans run non-destructive and UnifySameDomain gets a copy. Callers
    only read the properties. At most FACE_PROPS_KEPT faces are held (all dropped past that), so the faces of
    shapes freed long ago do not stay in memory."""
    bucket = _FACE_PROPS.setdefault(hash(face), [])
    for known, props in bucket:
        if known.IsEqual(face):
            return props
    props = surface_props(face)
    if len(_FACE_PROPS) > FACE_PROPS_KEPT:
        _FACE_PROPS.clear()
        bucket = _FACE_PROPS.setdefault(hash(face), [])
    bucket.append((face, props))
    return props


def boundary_length(shape: TopoDS_Shape) -> float:
    """Length of the edges of `shape` (a face's: its boundary, seams counted once per use)."""
    props = GProp_GProps()
    BRepGProp.LinearProperties_s(shape, props)
    return props.Mass()


def bounds_face(edge: TopoDS_Shape) -> bool:
    """Whether an edge, as met exploring a face, is on the face's boundary (FORWARD or REVERSED), not inside it
    (INTERNAL or EXTERNAL: a joint that ended inside the face without splitting it, which a STEP file drops)."""
    return edge.Orientation() in (TopAbs_FORWARD, TopAbs_REVERSED)


def bounded(face: TopoDS_Shape) -> bool:
    """Whether a face has a wire: one without stands for its whole, unbounded surface."""
    return TopExp_Explorer(face, TopAbs_WIRE).More()


def subshapes(shape: TopoDS_Shape, kind: TopAbs_ShapeEnum) -> list[TopoDS_Shape]:
    """The sub-shapes of `kind` in explorer order, repeats included (an edge of two faces comes twice)."""
    found = []
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    return found


def curve_edges(shape: TopoDS_Shape) -> Iterator[TopoDS_Edge]:
    """The edges of `shape` that have a curve (degenerate ones, at a pole, left out), in explorer order."""
    for edge in subshapes(shape, TopAbs_EDGE):
        edge = TopoDS.Edge(edge)
        if not BRep_Tool.Degenerated_s(edge):
            yield edge


def face_wires(face: TopoDS_Face) -> list[TopoDS_Wire]:
    """Outer wire first, then the others. Wires come out of the face with the face's orientation composed in,
    so their edge orientations are the ones the boundary really runs in."""
    outer = BRepTools.OuterWire_s(face)
    wires = [] if outer.IsNull() else [outer]
    it = TopoDS_Iterator(face)
    while it.More():
        child = it.Value()
        if child.ShapeType() == TopAbs_WIRE and not child.IsSame(outer):
            wires.append(TopoDS.Wire(child))
        it.Next()
    return wires


def diagonal(shape: TopoDS_Shape) -> float:
    """Bounding-box diagonal (of the geometry, not of a triangulation): sizes steps and meshes."""
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, False)
    return box.CornerMin().Distance(box.CornerMax())
