"""A planar or cylindrical mid-patch face clipped to the footprint of its partner faces.

The paper offsets the whole larger face of a pair. Where that face reaches past its partners (a plate under a
wall or a boss, a side wall whose partner stops at the floor, a slot's end whose outer wall turns into a block),
the offset lies over material of another thickness, or over a joint that the other patch covers anyway. The
part of the face that projects (along the patch normal) onto one of its partners is kept; extend-and-stitch
grows the clipped edges back to the neighbouring patches.
"""

import math

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon, BRepBuilderAPI_Transform
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism, BRepPrimAPI_MakeRevol
from OCP.BRepTools import BRepTools
from OCP.BRepGProp import BRepGProp
from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_IN, TopAbs_OUT
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Ax1, gp_Cylinder, gp_Dir, gp_Lin, gp_Pnt, gp_Trsf, gp_Vec

from ..constants import (
    BAY_SHARE, BOUNDARY_SAMPLES, CONFUSION, ENCLOSED_SHARE, MIN_CLIPPED_SHARE, MIN_PERIMETER, PARALLEL_AXES,
    SECTOR_INNER_SHARE, TONGUE_REACH,
)
from ..geom.booleans import split, unify
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import interior_point
from ..geom.solid_boundary import SolidBoundary
from ..geom.topology import ancestors, compound_of, diagonal, distance_to, indexed_map, surface_props
from ..protocol.errors import KernelError
from .wall_probe import WallProbe


def clip_to_partners(
    face: TopoDS_Face,
    partners: list[TopoDS_Face],
    fuzzy: float,
    narrow: float,
    narrow_end: float,
    exclude: list[TopoDS_Face] = (),
    wall: WallProbe | None = None,
) -> tuple[list[TopoDS_Face], bool]:
    """(the pieces of `face` over the footprint of `partners`, plus the narrow uncovered pieces, or [face] when
    nothing worth clipping; whether any of them lies beyond that footprint, True when the clip cannot tell).
    Pieces over one of `exclude` (the partners of the face's other thickness levels, whose own patches cover
    them) go whatever their width. An uncovered piece between two covered ones lies under something crossing
    the wall (a wall, a lug) and stays up to `narrow` wide, or wider where `wall` shows the wall running on under
    all of it (WallProbe.runs_through: the root of a thick land or a block, which get no patch of their own):
    the patch runs on across the junction. One at a dead
    end (an overshoot at a corner, a slot's end running into a block) stays up to `narrow_end` wide; past it
    the piece lies over other material, and the joints grow the clipped edge instead. A narrow piece at a dead
    end that reaches farther than TONGUE_REACH x `narrow_end` from the covered pieces is a tongue, not a corner's
    overshoot: where a wall meets a taller one at its end, the taller wall's end face is coplanar with the lower
    wall's skin and merges with it; its footprint lies on the taller wall, whose own patch covers it. A tongue
    goes only when `wall` shows most of its far part (past `narrow_end` from the covered pieces) on another
    wall (WallProbe.tongue): over a thick rib or a block no other patch covers it, and it stays.

    A planar face with planar partners is clipped by prisms of their outlines swept along its normal; a
    cylindrical face with coaxial cylindrical partners by the sectors their (u, v) ranges span about the axis.
    An excluded face's footprint keeps its holes: a level's partner may sit in a hole of another level's (a
    recess in a floor). Only planar faces take `exclude`.
    """
    if not partners:
        return [face], True
    surface = BRepAdaptor_Surface(face, True)
    excluded = []
    if surface.GetType() == GeomAbs_Plane and all(is_plane(p) for p in [*partners, *exclude]):
        reach = diagonal(face) + max(diagonal(p) for p in [*partners, *exclude])
        normal = gp_Vec(surface.Plane().Axis().Direction())
        prisms = [_prism(_outline(p), normal, reach) for p in partners]
        excluded = [_prism(p, normal, reach) for p in exclude]
    elif exclude:
        return [face], True
    elif surface.GetType() == GeomAbs_Cylinder:
        cylinders = [_coaxial(surface.Cylinder(), p, fuzzy) for p in partners]
        if any(c is None for c in cylinders):
            return [face], True
        reach = diagonal(face) + max(diagonal(p) for p in partners)
        radius = surface.Cylinder().Radius()
        prisms = [_sector(c, p, radius, reach) for c, p in zip(cylinders, partners)]
    else:
        return [face], True

    splitter = split(face, prisms + excluded, fuzzy)
    if splitter is None:
        return [face], True
    # One classifier per prism, loaded once, asked once per piece.
    classifiers = [BRepClass3d_SolidClassifier(prism) for prism in prisms]
    others = [BRepClass3d_SolidClassifier(prism) for prism in excluded]
    pieces = indexed_map(splitter.Shape(), TopAbs_FACE)
    faces = [TopoDS.Face(pieces.FindKey(i)) for i in range(1, pieces.Size() + 1)]
    points = [_point(piece) for piece in faces]
    elsewhere = [any(_inside(c, p, fuzzy) for c in others) for p in points]
    covered = [not e and any(_inside(c, p, fuzzy) for c in classifiers) for p, e in zip(points, elsewhere)]
    # How an uncovered piece touches the covered ones: a band between two of them, or a bay cut into one, is
    # never a tongue.
    flanked = _flanked(splitter.Shape(), pieces, covered) if not all(covered) else None
    cover = compound_of([f for f, c in zip(faces, covered) if c])
    areas = [surface_props(piece).Mass() for piece in faces]
    kept = []
    for i, piece in enumerate(faces):
        if covered[i]:
            kept.append(i)
            continue
        between = flanked is not None and flanked[i]
        if elsewhere[i]:
            continue
        if _width(piece, areas[i]) > (narrow if between else narrow_end):
            # A strict clip (narrow 0: a minor thickness level) keeps only what lies over the partners.
            if not (between and narrow > 0.0 and wall is not None and wall.runs_through(piece, narrow)):
                continue
        if not between and wall is not None and _reach(piece, cover) > TONGUE_REACH * narrow_end:
            if wall.tongue(piece, cover, narrow_end):
                continue
        kept.append(i)
    area = surface_props(face).Mass()
    kept_area = sum(areas[i] for i in kept)
    if not kept or kept_area >= (1.0 - MIN_CLIPPED_SHARE) * area:
        return [face], not all(covered)
    overhang = not all(covered[i] for i in kept)
    kept = [faces[i] for i in kept]
    merged = indexed_map(unify(kept, fuzzy), TopAbs_FACE) if len(kept) > 1 else None
    if merged is None:
        return kept, overhang
    return [TopoDS.Face(merged.FindKey(i)) for i in range(1, merged.Size() + 1)], overhang


def within_solid(
    face: TopoDS_Face, solid: SolidBoundary, fuzzy: float, negligible: float, skins: list[TopoDS_Shape] = ()
) -> list[TopoDS_Face]:
    """The pieces of a curved mid-patch face that lie in `solid`; [face] when none lies outside, when all that
    does reaches no farther than `negligible` past the cut, or when OCCT gives up. Offsetting a curved face keeps
    its (u, v) bounds (a cylinder's clip to its partners' sectors is about the axis only), so where the wall's
    rim is not square to the face (a dome cut by a plane off its centre, a tube cut by an oblique plane) the
    offset rim runs past the solid's boundary: cut there, the patch ends on the rim face as a wall's mid-surface
    does. A band within the rim tolerance stays: a drafted wall's patches all overshoot their rim by as little,
    planar ones included, and cutting only the curved ones would part them.

    `skins` (the face's source and its partners) lie half the wall from the face: they cut it only where the
    wall thins to nothing under it, so each is a tool of the split only when it comes within `fuzzy` of the
    face. The distance is far cheaper than a split by a surface parallel to the face, the slowest kind of
    split (seconds for one offset B-spline face)."""
    classifier = solid.classifier
    cut_by = _split_by_solid(face, solid, fuzzy, skins)
    if cut_by is None:
        return [face]
    shape, pieces = cut_by
    faces = [TopoDS.Face(pieces.FindKey(i)) for i in range(1, pieces.Size() + 1)]
    try:
        inside = [_inside(classifier, _point(piece), fuzzy) for piece in faces]
    except KernelError:
        return [face]  # a sliver with no point inside it: the cut is not to be trusted
    if all(inside) or not any(inside):
        return [face]
    cut = _cut_lengths(shape, pieces, inside)
    # A piece outside whose whole boundary is cut lies in a hole of the wall: a suppressed hole's filled loop,
    # which the patch spans on purpose. Only what runs out past the wall's edge goes.
    outside = [k for k in range(len(faces)) if not inside[k] and not _enclosed(faces[k], cut[k])]
    if all(surface_props(faces[k]).Mass() / max(cut[k], MIN_PERIMETER) <= negligible for k in outside):
        return [face]
    return [piece for k, piece in enumerate(faces) if k not in outside]


def _enclosed(piece: TopoDS_Face, cut: float) -> bool:
    """Whether the piece's boundary is all cut (`cut`: the length of it shared with pieces across the solid's
    boundary), so that it touches none of the face's own edges."""
    perimeter = _perimeter(piece)
    return perimeter - cut <= ENCLOSED_SHARE * perimeter


def _split_by_solid(face: TopoDS_Face, solid: SolidBoundary, fuzzy: float, skins):
    """(the split shape, its faces) of the face split by the solid's boundary, None when it is not cut. A curved
    face whose boundary stays in the solid is not split at all: a piece of it outside the solid would touch none
    of its edges, and such a piece (a filled hole) stays (within_solid), so the split could only give the face
    back, at the cost of intersecting it with the solid's nearby faces (most of the patch stage on parts with
    many bends or pipes). OCCT's fuzzy split can miss a section running at a shallow angle to the face's own
    rim (a tube's wall cut by an oblique plane): when it gives one piece, a curved face splits again without
    fuzz. A plane meets the faces that cut it along straight lines or conics, which the fuzzy split finds, and
    is split as it is (testing its boundary costs seconds on a large plate). Only the solid's faces near the
    face cut it (a split by the whole solid costs as much as all its faces), and `skins` only when they touch
    it."""
    curved = not is_plane(face)
    if curved and not _boundary_leaves(face, solid.classifier, fuzzy):
        return None
    near = solid.faces_near(face, fuzzy, skins)
    if near is None:
        return None
    for tolerance in (fuzzy, 0.0) if curved else (fuzzy,):
        splitter = split(face, [near], tolerance)
        if splitter is not None:
            pieces = indexed_map(splitter.Shape(), TopAbs_FACE)
            if pieces.Size() >= 2:
                return splitter.Shape(), pieces
    return None


def _boundary_leaves(face: TopoDS_Face, classifier: BRepClass3d_SolidClassifier, tolerance: float) -> bool:
    """Whether a point of the face's boundary (BOUNDARY_SAMPLES inside each edge) lies outside the solid."""
    fractions = [k / (BOUNDARY_SAMPLES + 1) for k in range(1, BOUNDARY_SAMPLES + 1)]
    for p in _edge_points(face, fractions):
        classifier.Perform(p, max(tolerance, CONFUSION))
        if classifier.State() == TopAbs_OUT:
            return True
    return False


def _edge_points(face: TopoDS_Face, fractions: list[float]):
    """Points of each edge of the face (degenerated ones left out) at these fractions of its parameter range."""
    edges = indexed_map(face, TopAbs_EDGE)
    for i in range(1, edges.Size() + 1):
        edge = TopoDS.Edge(edges.FindKey(i))
        if BRep_Tool.Degenerated_s(edge):
            continue
        curve = BRepAdaptor_Curve(edge)
        first, last = curve.FirstParameter(), curve.LastParameter()
        for fraction in fractions:
            yield curve.Value(first + (last - first) * fraction)


def _cut_lengths(shape: TopoDS_Shape, pieces, inside: list[bool]) -> list[float]:
    """Per piece, the length of its edges shared with a piece on the other side of the solid's boundary (the
    cut): a piece outside reaches area / cut past it, its band's width (a crescent's mean height)."""
    out = [0.0] * pieces.Size()
    for edge, owners in _edge_owners(shape, pieces):
        if len({inside[i] for i in owners}) < 2:
            continue
        length = _perimeter(edge)
        for i in owners:
            out[i] += length
    return out


def _edge_owners(shape: TopoDS_Shape, pieces):
    """Each edge of the split `shape` with the pieces (0-based, `pieces` order) that hold it."""
    edge_faces = ancestors(shape, TopAbs_EDGE, TopAbs_FACE)
    for e in range(1, edge_faces.Size() + 1):
        yield edge_faces.FindKey(e), {pieces.FindIndex(f) - 1 for f in edge_faces.FindFromIndex(e)}


def _reach(piece: TopoDS_Face, cover: TopoDS_Shape) -> float:
    """How far an uncovered piece reaches from the covered pieces (`cover`): the largest distance to them of
    its vertices and edge midpoints (0 when nothing is covered). A band along a covered edge reaches its width,
    a tongue standing off one its length, however narrow it is."""
    farthest = 0.0
    for point in _edge_points(piece, [0.0, 0.5, 1.0]):
        distance = distance_to(point, cover)
        if distance is not None:
            farthest = max(farthest, distance)
    return farthest


def _point(piece: TopoDS_Face):
    return interior_point(OutwardNormals(piece), diagonal(piece))[0]


def _flanked(shape: TopoDS_Shape, pieces, covered: list[bool]) -> list[bool]:
    """Per piece (0-based, `pieces` order), whether it is uncovered and covered pieces flank it: it shares edges
    with two of them (a band across the footprint), or its edges run along covered ones for at least BAY_SHARE
    of its boundary (a bay cut into the footprint from its edge: where a boss or a rib merges into one skin of
    the wall, that skin stops around the merge and the other runs on)."""
    neighbours: list[set[int]] = [set() for _ in range(pieces.Size())]
    along = [0.0] * pieces.Size()
    for edge, owners in _edge_owners(shape, pieces):
        near_covered = any(covered[j] for j in owners)
        length = _perimeter(edge) if near_covered else 0.0
        for i in owners:
            neighbours[i].update(j for j in owners if j != i and covered[j])
            if not covered[i]:
                along[i] += length
    return [
        not covered[i] and (len(neighbours[i]) >= 2 or along[i] >= BAY_SHARE * _perimeter(pieces.FindKey(i + 1)))
        for i in range(pieces.Size())
    ]


def _perimeter(shape: TopoDS_Shape) -> float:
    """The length of the shape's edges (of an edge: its length)."""
    props = GProp_GProps()
    BRepGProp.LinearProperties_s(shape, props)
    return props.Mass()


def _width(face: TopoDS_Face, area: float) -> float:
    """Mean width of a face of `area`, 2 x area / perimeter: the width of a long band, the radius of a disc."""
    return 2.0 * area / max(_perimeter(face), MIN_PERIMETER)


def is_plane(face: TopoDS_Face) -> bool:
    return BRepAdaptor_Surface(face, True).GetType() == GeomAbs_Plane


def _coaxial(cylinder: gp_Cylinder, partner: TopoDS_Face, tolerance: float) -> gp_Cylinder | None:
    """The partner's cylinder when it shares `cylinder`'s axis, else None."""
    surface = BRepAdaptor_Surface(partner, True)
    if surface.GetType() != GeomAbs_Cylinder:
        return None
    axis, other = cylinder.Axis(), surface.Cylinder().Axis()
    if axis.IsParallel(other, PARALLEL_AXES) and gp_Lin(axis).Distance(other.Location()) <= tolerance:
        return surface.Cylinder()
    return None


def _sector(cylinder: gp_Cylinder, partner: TopoDS_Face, radius: float, reach: float) -> TopoDS_Shape:
    """The solid sector about the partner's axis (`cylinder`: the partner's surface) spanning its (u, v)
    ranges, from half of `radius` (the clipped face's) or the partner's, whichever is less, out to `reach` past
    the partner: the partner's footprint on the clipped face (exact for a partner bounded by isolines, the usual
    wall of a bend or a slot's end; a wider outline only keeps more). It stops short of the axis, where a
    revolved section degenerates and the splitter then misses the sector's sides."""
    frame = cylinder.Position()
    u0, u1, v0, v1 = BRepTools.UVBounds_s(partner)
    x, y, z = gp_Vec(frame.XDirection()), gp_Vec(frame.YDirection()), gp_Vec(frame.Direction())
    start = x.Multiplied(math.cos(u0)).Added(y.Multiplied(math.sin(u0)))
    origin = gp_Vec(frame.Location().XYZ())
    inner, outer = SECTOR_INNER_SHARE * min(radius, cylinder.Radius()), cylinder.Radius() + reach

    def corner(r, v):
        return gp_Pnt(origin.Added(start.Multiplied(r)).Added(z.Multiplied(v)).XYZ())

    outline = BRepBuilderAPI_MakePolygon(corner(inner, v0), corner(outer, v0), corner(outer, v1), corner(inner, v1), True)
    section = BRepBuilderAPI_MakeFace(outline.Wire(), True).Face()
    # u grows about X ^ Y, which is the frame's main direction only when the frame is right-handed.
    turn = gp_Ax1(frame.Location(), gp_Dir(x.Crossed(y)))
    return BRepPrimAPI_MakeRevol(section, turn, min(u1 - u0, 2.0 * math.pi)).Shape()


def _outline(partner: TopoDS_Face) -> TopoDS_Face:
    """The partner within its outer wire, its holes left out: where a boss or a pocket interrupts the partner,
    the patch goes on (a hole through the wall is a hole of the reference face too, and stays)."""
    return BRepBuilderAPI_MakeFace(BRepTools.OuterWire_s(partner), True).Face()


def _prism(outline: TopoDS_Face, normal: gp_Vec, reach: float) -> TopoDS_Shape:
    """A planar face swept along the normal from -reach to +reach: its footprint on any parallel plane."""
    shift = gp_Trsf()
    shift.SetTranslation(normal.Multiplied(-reach))
    start = BRepBuilderAPI_Transform(outline, shift, True).Shape()
    return BRepPrimAPI_MakePrism(start, normal.Multiplied(2.0 * reach)).Shape()


def _inside(classifier: BRepClass3d_SolidClassifier, point, tolerance: float) -> bool:
    classifier.Perform(gp_Pnt(*point), max(tolerance, CONFUSION))
    return classifier.State() == TopAbs_IN
