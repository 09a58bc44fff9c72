"""`extend_edges`: a strip face grown from a free edge of a mid-patch, outward along the patch's tangent plane,
by a length Rust chose at each sample of the edge (the samples of `probe_edges`).

The strip is the ruled surface between the edge and its far curve (the sample points moved outward): flat
for a straight edge reaching a plane, twisted where the lengths vary along a curved edge. Its near edge
coincides with the patch's edge, so the next `fuse` shares it.
"""

import math

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepFill import BRepFill
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.collections import HArray1_gp_Pnt
from OCP.GC import GC_MakeSegment
from OCP.GeomAbs import GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Line, GeomAbs_Plane
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Ax2, gp_Ax3, gp_Circ, gp_Cylinder, gp_Dir, gp_Pln, gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape, TopoDS_Wire

from ..constants import (
    AXIAL_DEG, CONFUSION, MERIDIAN_ISO, PCURVE_SAMPLES, STRIP_RELATIVE_TOLERANCE, SWEEP_PARALLEL,
)
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import interior_point
from ..geom.topology import diagonal, indexed_map
from ..geom.vectors import Vec, add_scaled, cross, dot, norm, scale, sub, xyz
from ..protocol.errors import KernelError
from .edge_probe import sample_edge


def strip(
    face: TopoDS_Face, edge: TopoDS_Shape, lengths: list[float], onto_face: bool = False, along: Vec | None = None
) -> TopoDS_Face:
    """Oriented like the patch face (normals agree at the middle of the edge), so the faces of one patch can
    be merged and shells stay consistently oriented. `onto_face`: the edge grows onto the partner patch's own
    face (a T-joint), which a strip on a cylinder may then keep to (`_axial_sweep`). `along`: the edge swept
    straight by this vector (an upright band across a thickness step, lengths all 0), oriented along the edge's
    outward direction as an upright step quad is; or, with lengths, a ramp to the samples moved outward by them
    and by `along`, oriented like the patch."""
    if along is not None:
        return _step(face, edge, lengths, along)
    samples = sample_edge(face, edge, len(lengths))
    made = _strip(face, edge, samples, lengths, onto_face)
    return _oriented_like(made, samples[len(samples) // 2].normal)


def _step(face: TopoDS_Face, edge: TopoDS_Shape, lengths: list[float], along: Vec) -> TopoDS_Face:
    """The bridge of a step swept `along` (see `strip`): upright when the lengths are 0, else a ramp whose far
    curve follows the edge's outline one run inside, sampled as finely as the edge's pcurves (the probe's few
    samples would smooth a wavy outline away) at the one run Rust gave every sample."""
    run = max(lengths)
    if run <= 0.0:
        made = _prism(edge, along)
        if made is None:
            raise KernelError("the edge could not be swept across the step")
        samples = sample_edge(face, edge, len(lengths))
        return _oriented_like(made, samples[len(samples) // 2].outward)
    fine = sample_edge(face, edge, max(len(lengths), PCURVE_SAMPLES))
    far = [add_scaled(add_scaled(s.point, s.outward, run), along, 1.0) for s in fine]
    tolerance = STRIP_RELATIVE_TOLERANCE * max(norm(sub(far[-1], far[0])), run, norm(along))
    return _oriented_like(_ruled(edge, fine, far, tolerance), fine[len(fine) // 2].normal)


def _oriented_like(made: TopoDS_Face, normal: Vec) -> TopoDS_Face:
    _, own = interior_point(OutwardNormals(made), diagonal(made))
    return made if dot(own, normal) >= 0.0 else TopoDS.Face(made.Reversed())


def _strip(face: TopoDS_Face, edge: TopoDS_Shape, samples: list, lengths: list[float], onto_face: bool) -> TopoDS_Face:
    far = [add_scaled(s.point, s.outward, length) for s, length in zip(samples, lengths)]
    first = samples[0].outward
    axis = _cylinder_axis(face)
    one_length = max(lengths) - min(lengths) <= SWEEP_PARALLEL * max(lengths)
    if all(norm(sub(s.outward, first)) <= SWEEP_PARALLEL for s in samples) and one_length:
        # One direction, one length: the edge swept straight, which keeps the patch's own surface where it
        # can (a circle along its cylinder's axis stays that cylinder), so the strip merges into the patch.
        sweep = scale(first, sum(lengths) / len(lengths))
        made = _along_cylinder(face, axis, edge, sweep) if axis is not None else None
        made = made if made is not None else _prism(edge, sweep)
        if made is not None:
            return made
    if one_length:
        made = _along_meridian(face, edge, samples[len(samples) // 2], sum(lengths) / len(lengths))
        if made is not None:
            return made
    # Only onto a face: the partner of an L-joint grows a ruled strip too, and the kernel could not cut the
    # cylinder band with it where the two run side by side (a branch across its main's seam).
    axial = _axial_sweep(axis, samples, lengths) if onto_face and axis is not None else None
    if axial is not None:
        made = _cylinder_band(face, axis, edge, axial)
        made = made if made is not None else _prism(edge, axial)
        if made is not None:
            return made
    # Forward, so the ruled surface joins the near edge's first vertex to the far curve's first point.
    near = TopoDS.Edge(edge.Oriented(TopAbs_FORWARD))
    near_curve = BRepAdaptor_Curve(near)
    tolerance = STRIP_RELATIVE_TOLERANCE * max(norm(sub(far[-1], far[0])), max(lengths))
    if near_curve.GetType() != GeomAbs_Line or not _collinear(far, tolerance):
        return _ruled(edge, samples, far, tolerance)
    plane = _plane_of(face)
    if plane is not None and all(abs(plane.Distance(gp_Pnt(*p))) <= tolerance for p in far):
        # On the patch's own plane: a plane face, so unify_same_domain can merge it into the patch.
        return _planar_quad(plane, [samples[0].point, samples[-1].point, far[-1], far[0]])
    return _ruled_to(near, GC_MakeSegment(gp_Pnt(*far[0]), gp_Pnt(*far[-1])).Value())


def _ruled(edge: TopoDS_Shape, samples: list, far: list[Vec], tolerance: float) -> TopoDS_Face:
    """The ruled face between the edge and the curve interpolated through `far` (one point per sample)."""
    _refuse_fold(samples, far)
    points = HArray1_gp_Pnt(1, len(far))
    for k, p in enumerate(far):
        points.SetValue(k + 1, gp_Pnt(*p))
    interpolate = GeomAPI_Interpolate(points, False, tolerance)
    interpolate.Perform()
    if not interpolate.IsDone():
        raise KernelError("the strip's far curve could not be interpolated")
    return _ruled_to(TopoDS.Edge(edge.Oriented(TopAbs_FORWARD)), interpolate.Curve())


def _ruled_to(near: TopoDS_Shape, far_curve) -> TopoDS_Face:
    """The ruled face between the edge `near` (forward) and `far_curve`."""
    far_edge = BRepBuilderAPI_MakeEdge(far_curve).Edge()
    result = BRepFill.Face_s(near, far_edge)
    if result.IsNull() or not BRepCheck_Analyzer(result).IsValid():
        raise KernelError("the strip face is not valid")
    return result


def _prism(edge: TopoDS_Shape, sweep: Vec) -> TopoDS_Face | None:
    """The edge swept straight by `sweep` (a surface of extrusion), or None when the kernel gives up."""
    prism = BRepPrimAPI_MakePrism(TopoDS.Edge(edge.Oriented(TopAbs_FORWARD)), gp_Vec(*sweep))
    if not prism.IsDone():
        return None
    swept = TopExp_Explorer(prism.Shape(), TopAbs_FACE)
    return TopoDS.Face(swept.Current()) if swept.More() else None


def _cylinder_axis(face: TopoDS_Face) -> Vec | None:
    """The axis direction of a cylindrical face's frame (its v direction), None for other surfaces."""
    adaptor = BRepAdaptor_Surface(face, False)
    if adaptor.GetType() != GeomAbs_Cylinder:
        return None
    return xyz(adaptor.Cylinder().Axis().Direction())


def _along_cylinder(face: TopoDS_Face, axis: Vec, edge: TopoDS_Shape, sweep: Vec) -> TopoDS_Face | None:
    """On a cylindrical patch (`axis`), an edge swept along the axis as a face of the patch's own cylinder (a
    prism would be a surface of extrusion, which unify_same_domain cannot merge into the cylinder)."""
    length = norm(sweep)
    along = dot(sweep, axis)
    if abs(abs(along) - length) > SWEEP_PARALLEL * length:
        return None
    curve = BRepAdaptor_Curve2d(TopoDS.Edge(edge), face)
    start, end = curve.Value(curve.FirstParameter()), curve.Value(curve.LastParameter())
    if abs(start.Y() - end.Y()) > SWEEP_PARALLEL * max(1.0, length):
        return None  # not an iso-v circle of the cylinder
    # v runs along the axis direction of the cylinder's frame, in length units.
    v0 = start.Y()
    u0, u1 = sorted((start.X(), end.X()))
    if u1 - u0 <= 0.0:
        return None
    v1 = v0 + along
    return _band(face, u0, u1, min(v0, v1), max(v0, v1))


def _band(face: TopoDS_Face, u0: float, u1: float, v0: float, v1: float) -> TopoDS_Face | None:
    """The face of `face`'s own surface over u0..u1 x v0..v1, None when the kernel gives up. It is made on a copy
    of the surface. OCCT moves a u range lying past the period back by one (an arc at u 2pi..3pi becomes
    0..pi); on the patch's very surface object the fuse would give the strip the pcurve their shared edge has
    on the patch, a period away from the strip's wire, and the strip would come out of the fuse inverted
    (negative area, invalid), taking the patch face with it. On a copy, the fuse computes the strip's pcurves
    anew; unify_same_domain still merges the strip into the patch (it compares the surfaces' geometry)."""
    maker = BRepBuilderAPI_MakeFace(BRep_Tool.Surface_s(face).Copy(), u0, u1, v0, v1, CONFUSION)
    return maker.Face() if maker.IsDone() else None


def _along_meridian(face: TopoDS_Face, edge: TopoDS_Shape, sample, length: float) -> TopoDS_Face | None:
    """On a cone patch, an edge along a parallel (an iso-v circle or arc) grown by `length` along the meridian
    (the ruling) as a face of the patch's own cone, so the strip merges into the patch (a ruled strip is a face
    of its own, off the surface by its chords). By symmetry the outward direction is along the meridian all
    round a parallel: checked at the edge's middle `sample`. None for other surfaces and edges (spheres and
    tori were tried: on a part with toroidal blends their strips split more patches than they joined)."""
    adaptor = BRepAdaptor_Surface(face, False)
    if adaptor.GetType() != GeomAbs_Cone:
        return None
    curve = BRepAdaptor_Curve2d(TopoDS.Edge(edge), face)
    first, last = curve.FirstParameter(), curve.LastParameter()
    uv = [curve.Value(first + (last - first) * k / PCURVE_SAMPLES) for k in range(PCURVE_SAMPLES + 1)]
    us, vs = [p.X() for p in uv], [p.Y() for p in uv]
    u0, u1, v = min(us), max(us), vs[0]
    if u1 - u0 <= 0.0 or max(vs) - min(vs) > MERIDIAN_ISO * max(1.0, abs(v)):
        return None
    point, along_u, along_v = gp_Pnt(), gp_Vec(), gp_Vec()
    adaptor.D1(0.5 * (u0 + u1), v, point, along_u, along_v)
    speed = along_v.Magnitude()
    if speed <= CONFUSION:
        return None
    meridian = scale(xyz(along_v), 1.0 / speed)
    if abs(dot(meridian, sample.outward)) < 1.0 - MERIDIAN_ISO:
        return None
    step = length / speed * (1.0 if dot(meridian, sample.outward) > 0.0 else -1.0)
    made = _band(face, u0, u1, min(v, v + step), max(v, v + step))
    return made if made is not None and BRepCheck_Analyzer(made).IsValid() else None


# A curved edge of a cylindrical patch whose outward directions mostly (the median) lie within this angle of
# the axis (degrees) is swept along the axis: the saddle where a branch pipe meets its main.


def _axial_sweep(axis: Vec, samples: list, lengths: list[float]) -> Vec | None:
    """The sweep along a cylindrical patch's `axis` by the longest length, when the samples grow along the
    axis (one way; most within AXIAL_DEG, none against it). A ruled strip through a few samples of a closed
    saddle edge leaves the cylinder between them, and its crossing with the main pipe then misses the branch's
    own surface; the edge swept along the axis stays on the cylinder. The longer sweep at samples nearer their
    partner is an overshoot the trimming drops."""
    along = sorted(dot(s.outward, axis) for s in samples)
    median, limit = along[len(along) // 2], math.cos(math.radians(AXIAL_DEG))
    # The ends may turn across the axis: where an equal-radius branch touches its main, the saddle's
    # halves end upright.
    if median >= limit and along[0] >= -SWEEP_PARALLEL:
        return scale(axis, max(lengths))
    if median <= -limit and along[-1] <= SWEEP_PARALLEL:
        return scale(axis, -max(lengths))
    return None


def _cylinder_band(face: TopoDS_Face, axis: Vec, edge: TopoDS_Shape, sweep: Vec) -> TopoDS_Face | None:
    """The edge swept along the axis as a face of the patch's own cylinder: the band of the cylinder from the
    edge's lowest to its highest point (in the sweep's direction) and on by the sweep, less the patch face.
    A prism of a saddle edge is a surface of extrusion, which the kernel intersects with another pipe's
    cylinder numerically: at an equal-radius tee, where the two touch at the saddle's ends, it broke the faces
    it cut (salome_pipe). Two true cylinders meet in its analytic case. None when the cut leaves other than
    one face (a patch piece not covering the band above the edge)."""
    surface = BRep_Tool.Surface_s(face)
    curve = BRepAdaptor_Curve2d(TopoDS.Edge(edge), face)
    first, last = curve.FirstParameter(), curve.LastParameter()
    uv = [curve.Value(first + (last - first) * k / PCURVE_SAMPLES) for k in range(PCURVE_SAMPLES + 1)]
    us, vs = [p.X() for p in uv], [p.Y() for p in uv]
    u0, u1 = min(us), max(us)
    if u1 - u0 <= 0.0:
        return None
    along = dot(sweep, axis)  # v runs along the axis of the cylinder's frame, in length units
    v0, v1 = (min(vs) + min(along, 0.0), max(vs) + max(along, 0.0))
    band = BRepBuilderAPI_MakeFace(surface, u0, u1, v0, v1, CONFUSION)
    if not band.IsDone():
        return None
    cut = BRepAlgoAPI_Cut(band.Face(), face)
    if not cut.IsDone():
        return None
    pieces = indexed_map(cut.Shape(), TopAbs_FACE)
    if pieces.Size() != 1:
        return None
    made = TopoDS.Face(pieces.FindKey(1))
    return made if BRepCheck_Analyzer(made).IsValid() else None


def _plane_of(face: TopoDS_Face) -> gp_Pln | None:
    surface = BRepAdaptor_Surface(face, False)
    return surface.Plane() if surface.GetType() == GeomAbs_Plane else None


def _closed_polygon(points: list[Vec]) -> TopoDS_Wire:
    polygon = BRepBuilderAPI_MakePolygon()
    for p in points:
        polygon.Add(gp_Pnt(*p))
    polygon.Close()
    return polygon.Wire()


def _planar_quad(plane: gp_Pln, points: list[Vec]) -> TopoDS_Face:
    maker = BRepBuilderAPI_MakeFace(plane, _closed_polygon(points), True)
    if not maker.IsDone():
        raise KernelError("the planar strip could not be made")
    return maker.Face()


def corner(points: list[Vec], normal: Vec, axis: tuple[Vec, Vec] | None = None) -> TopoDS_Face:
    """The quad v, a, c, b filling the notch between two strips grown from the edges meeting at a corner v of
    a patch: a and b are their far corners over v, c closes the parallelogram. Plane if flat, else ruled
    between v->a and b->c; oriented along the patch's `normal` at v. With `axis` (a point, a direction) the
    quad is a band between two coaxial arcs (a step bridge round a rounded corner, `_coaxial_band`)."""
    made = _coaxial_band(points, axis) if axis is not None else _corner(points)
    return _oriented_like(made, normal)


def _coaxial_band(points: list[Vec], axis: tuple[Vec, Vec]) -> TopoDS_Face:
    """The ruled band between the arc points[0] -> points[3] and the arc points[1] -> points[2], both about
    `axis` and turning counter-clockwise about its direction through the same angle: a band of a cone, a
    cylinder or an annulus, bounded by exact circles so that the fuse shares them with the patches they lie on."""
    origin, direction = axis
    band = _on_one_cylinder(points, origin, direction)
    if band is not None:
        return band
    first = _arc(points[0], points[3], origin, direction)
    second = _arc(points[1], points[2], origin, direction)
    result = BRepFill.Face_s(first, second)
    if result.IsNull() or not BRepCheck_Analyzer(result).IsValid():
        raise KernelError("the band between two coaxial arcs is not valid")
    return result


def _on_one_cylinder(points: list[Vec], origin: Vec, direction: Vec) -> TopoDS_Face | None:
    """The band as a face of the cylinder both arcs lie on, when they have one radius and lie at two heights (a
    gap in a cylindrical patch's own surface), so that it merges into the patch; None otherwise. A ruled face
    between two arcs of one cylinder is a B-spline, which no merge recognises."""
    centre_a, radial_a, radius_a, angle = _turn(points[0], points[3], origin, direction)
    centre_b, _, radius_b, _ = _turn(points[1], points[2], origin, direction)
    height = dot(sub(centre_b, centre_a), direction)
    if abs(radius_a - radius_b) > CONFUSION or abs(height) <= CONFUSION:
        return None
    frame = gp_Ax3(gp_Pnt(*centre_a), gp_Dir(*direction), gp_Dir(*radial_a))
    low, high = min(0.0, height), max(0.0, height)
    maker = BRepBuilderAPI_MakeFace(gp_Cylinder(frame, radius_a), 0.0, angle, low, high)
    if not maker.IsDone() or not BRepCheck_Analyzer(maker.Face()).IsValid():
        return None
    return maker.Face()


def _arc(start: Vec, end: Vec, origin: Vec, direction: Vec) -> TopoDS_Shape:
    """The edge of the circle about the axis (origin, unit direction) through `start`, from it counter-clockwise
    about the direction to the angle of `end`."""
    centre, radial, radius, angle = _turn(start, end, origin, direction)
    circle = gp_Circ(gp_Ax2(gp_Pnt(*centre), gp_Dir(*direction), gp_Dir(*radial)), radius)
    return BRepBuilderAPI_MakeEdge(circle, 0.0, angle).Edge()


def _turn(start: Vec, end: Vec, origin: Vec, direction: Vec) -> tuple[Vec, Vec, float, float]:
    """(centre, radial vector, radius, angle) of the circle about the axis (origin, unit direction) through
    `start`, the angle counter-clockwise about the direction from `start` to `end` (0..2 pi)."""
    centre = add_scaled(origin, direction, dot(sub(start, origin), direction))
    radial = sub(start, centre)
    radius = norm(radial)
    if radius <= CONFUSION:
        raise KernelError("an arc of a step bridge has no radius")
    across = cross(direction, scale(radial, 1.0 / radius))
    towards = sub(end, add_scaled(origin, direction, dot(sub(end, origin), direction)))
    angle = math.atan2(dot(towards, across), dot(towards, scale(radial, 1.0 / radius))) % (2.0 * math.pi)
    return centre, radial, radius, angle


def _corner(points: list[Vec]) -> TopoDS_Face:
    v, a, c, b = points
    planar = BRepBuilderAPI_MakeFace(_closed_polygon(points), True)
    if planar.IsDone():
        # A plane face where the quad is flat (always, on a planar patch): unify_same_domain merges it.
        return planar.Face()
    first = BRepBuilderAPI_MakeEdge(gp_Pnt(*v), gp_Pnt(*a)).Edge()
    second = BRepBuilderAPI_MakeEdge(gp_Pnt(*b), gp_Pnt(*c)).Edge()
    result = BRepFill.Face_s(first, second)
    if result.IsNull() or not BRepCheck_Analyzer(result).IsValid():
        raise KernelError("the corner face is not valid")
    return result


def _refuse_fold(samples: list, far: list[Vec]) -> None:
    """A strip grown past the radius of a concave arc folds over itself (the far curve runs backwards); the
    kernel accepts the face and the fuse then cuts it into invalid slivers, so refuse it here."""
    for k in range(len(far) - 1):
        if dot(sub(far[k + 1], far[k]), sub(samples[k + 1].point, samples[k].point)) <= 0.0:
            raise KernelError("the strip would fold over itself (grown past the radius of a concave edge)")


def _collinear(points: list[Vec], tolerance: float) -> bool:
    a, b = points[0], points[-1]
    axis = sub(b, a)
    length = norm(axis)
    if length == 0.0:
        return False
    return all(norm(cross(sub(p, a), axis)) / length <= tolerance for p in points)
