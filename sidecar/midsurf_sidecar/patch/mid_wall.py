"""A face moved to mid-wall point by point, for a wall whose thickness varies along it (a tapered blade, a cast
web): one offset is mid-way along one line only.

The face's surface, as a B-spline, has each pole moved along the inward normal at its Greville point by half
the distance, along that normal, to the partner faces (quasi-interpolation of the mid-points: exact for a
thickness linear in the parameters over a plane, and off by the thickness's second variation times the pole
spacing squared otherwise). The result is checked against the true mid-points at samples of the face, with
finer spans when it misses. The moved surface keeps the face's parameters, so the face's boundary is rebuilt
from its own parameter-space curves. Where that cannot be done (a periodic or an analytic surface, whose
B-spline form has other parameters; no partner found; mid-points missed even with fine spans; a face that fails
the kernel's check) the face is offset at the mean instead.
"""

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepLib import BRepLib
from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
from OCP.Geom import (
    Geom_BSplineSurface, Geom_CylindricalSurface, Geom_Line, Geom_RectangularTrimmedSurface, Geom_SphericalSurface,
)
from OCP.GeomAbs import GeomAbs_BezierSurface, GeomAbs_BSplineSurface, GeomAbs_Cylinder, GeomAbs_Plane, GeomAbs_Sphere
from OCP.GeomAPI import GeomAPI_IntCS
from OCP.GeomConvert import GeomConvert
from OCP.GeomLProp import GeomLProp_SLProps
from OCP.IntCurvesFace import IntCurvesFace_ShapeIntersector
from OCP.ShapeFix import ShapeFix_Face
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_VERTEX, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face
from OCP.gp import gp_Dir, gp_Lin, gp_Pnt, gp_Vec

from ..constants import (
    CONFUSION,
    INFINITE_PARAMETER,
    MID_WALL_ACCURACY,
    MID_WALL_CHECKS,
    MID_WALL_DEGREE,
    MID_WALL_REACH,
    MID_WALL_ROOM,
    MID_WALL_SPANS,
    NORMAL_RESOLUTION,
    PARALLEL_AXES,
)
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import area_samples
from ..geom.topology import diagonal, subshapes
from ..geom.uv_box import face_on_box, fills_its_box
from .face_offset import offset_face

MOVABLE_KINDS = (GeomAbs_BSplineSurface, GeomAbs_BezierSurface, GeomAbs_Plane)


def mid_wall_face(face: TopoDS_Face, partners: list[TopoDS_Face], mean_offset: float) -> TopoDS_Face:
    """`face` moved into the material to half-way to `partners` at every point (`mean_offset` < 0: the offset at
    the mean thickness, used where that cannot be done). A cylinder whose partners are cylinders on one axis
    parallel to its own goes onto the mean cylinder (`_mean_cylinder`), a sphere whose partners are spheres on one
    centre onto the mean sphere (`_mean_sphere`)."""
    kind = BRepAdaptor_Surface(face, False).GetType()
    if kind == GeomAbs_Cylinder:
        moved = _mean_cylinder(face, partners)
    elif kind == GeomAbs_Sphere:
        moved = _mean_sphere(face, partners)
    else:
        moved = _moved(face, partners, mean_offset)
    return moved if moved is not None else offset_face(face, mean_offset)


def _mean_sphere(face: TopoDS_Face, partners: list[TopoDS_Face]) -> TopoDS_Face | None:
    """`face` on the sphere on the mean of its centre and its partners' (one centre) with the mean radius, in the
    same parameters (the axis system moved, not turned): the dome of a vault whose skins were drawn on centres
    apart, meeting the vault's mean cylinder (`_mean_cylinder`) along their common circle as its skins meet.
    None when the partners are not such spheres."""
    surfaces = _all_of_kind([face, *partners], GeomAbs_Sphere)
    if surfaces is None or not partners:
        return None
    sphere, others = surfaces[0].Sphere(), [s.Sphere() for s in surfaces[1:]]
    offsets = [gp_Vec(sphere.Location(), o.Location()) for o in others]
    if any(v.Subtracted(offsets[0]).Magnitude() > CONFUSION for v in offsets[1:]):
        return None
    radius = 0.5 * (sphere.Radius() + others[0].Radius())
    return _sound_on(Geom_SphericalSurface(sphere.Position().Translated(offsets[0] * 0.5), radius), face)


def _mean_cylinder(face: TopoDS_Face, partners: list[TopoDS_Face]) -> TopoDS_Face | None:
    """`face` on the cylinder on the mean of its axis and its partners' (one axis, parallel to its own) with the
    mean radius, in the same parameters (the axis system moved across, not turned): the mid-surface of a bend
    whose two arcs were drawn on centres apart. Each skin's tangent line with a flat beside the bend lies on the
    flat's normal at the same angle, so the mean cylinder runs into the flat's mid-plane there, tangent to it,
    whatever the flat's thickness. Along the axis it runs half-way between the skins' ends (`_mean_span`) where
    it can. None when the partners are not such cylinders."""
    surfaces = _all_of_kind([face, *partners], GeomAbs_Cylinder)
    if surfaces is None or not partners:
        return None
    cylinder, others = surfaces[0].Cylinder(), [s.Cylinder() for s in surfaces[1:]]
    axis = cylinder.Axis()
    if not all(other.Axis().IsParallel(axis, PARALLEL_AXES) for other in others):
        return None
    location = cylinder.Location()
    offsets = [gp_Vec(location, o.Location()) for o in others]
    direction = gp_Vec(axis.Direction())
    across = [v - direction * v.Dot(direction) for v in offsets]
    if any(a.Subtracted(across[0]).Magnitude() > CONFUSION for a in across[1:]):
        return None
    radius = 0.5 * (cylinder.Radius() + others[0].Radius())
    mean = Geom_CylindricalSurface(cylinder.Position().Translated(across[0] * 0.5), radius)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    # Only a face that is its whole (u, v) box (four iso-lines) has a range that alone can be moved.
    span = _mean_span((v0, v1), partners, cylinder) if fills_its_box(face) else None
    moved = face_on_box(mean, (u0, u1, *span), face) if span is not None else None
    return moved or _sound_on(mean, face)


def _mean_span(span: tuple[float, float], partners: list[TopoDS_Face], cylinder) -> tuple[float, float] | None:
    """The axial range (the cylinder's v) half-way between the face's (`span`) and its partners': a bend between
    two others (a tub's bottom edge between its corners) ends where they begin, and on axes apart the skins' ends
    lie apart along the axis too, by the other bends' offsets."""
    v0, v1 = span
    origin, direction = cylinder.Location(), gp_Vec(cylinder.Axis().Direction())
    corners = [BRep_Tool.Pnt_s(TopoDS.Vertex(v)) for p in partners for v in subshapes(p, TopAbs_VERTEX)]
    along = [gp_Vec(origin, corner).Dot(direction) for corner in corners]
    if not along:
        return None
    low, high = 0.5 * (v0 + min(along)), 0.5 * (v1 + max(along))
    return (low, high) if high - low > CONFUSION else None


def _all_of_kind(faces: list[TopoDS_Face], kind) -> list[BRepAdaptor_Surface] | None:
    """The faces' surfaces (placed), None unless every one is of `kind`."""
    surfaces = [BRepAdaptor_Surface(f, True) for f in faces]
    return surfaces if all(s.GetType() == kind for s in surfaces) else None


def _sound_on(surface, face: TopoDS_Face) -> TopoDS_Face | None:
    """`face` rebuilt on `surface` (`_face_on`), None when that fails or the face fails the kernel's check."""
    try:
        rebuilt = _face_on(surface, face)
    except Exception:
        return None
    return rebuilt if rebuilt is not None and BRepCheck_Analyzer(rebuilt).IsValid() else None


def _moved(face: TopoDS_Face, partners: list[TopoDS_Face], mean_offset: float) -> TopoDS_Face | None:
    if not partners or BRepAdaptor_Surface(face, False).GetType() not in MOVABLE_KINDS:
        return None
    location = TopLoc_Location()
    surface = BRep_Tool.Surface_s(face, location)
    bounds = _within(BRepTools.UVBounds_s(face), surface.Bounds())
    room = _room(surface, bounds, MID_WALL_ROOM * 2.0 * abs(mean_offset))
    try:
        base = GeomConvert.SurfaceToBSplineSurface_s(Geom_RectangularTrimmedSurface(surface, *room))
    except Exception:
        return None
    if base.IsUPeriodic() or base.IsVPeriodic():
        return None
    base.Transform(location.Transformation())
    rays = _Rays(partners, MID_WALL_REACH * 2.0 * abs(mean_offset))
    inward = 1.0 if face.Orientation() == TopAbs_REVERSED else -1.0
    checks = _mid_points(face, rays)
    if not checks:
        return None
    # Each round splits the spans again: poles closer together follow a curved face's normals better.
    for spans in MID_WALL_SPANS:
        spline = base.Copy()
        _refine(spline, bounds, spans)
        if not _move_poles(spline, inward, rays):
            return None
        if all(spline.Value(u, v).Distance(mid) <= MID_WALL_ACCURACY * across for u, v, mid, across in checks):
            break
    else:
        return None
    return _sound_on(spline, face)


class _Rays:
    """The nearest of the partner faces along a line, up to `reach`; or of their surfaces, past the faces'
    boundaries (where the moved surface runs on past the face, its thickness carried on as the partners'
    surfaces run on)."""

    def __init__(self, partners: list[TopoDS_Face], reach: float):
        self.surfaces = [BRep_Tool.Surface_s(p) for p in partners]
        self.reach = reach
        # Loaded once: the intersector keeps each face's classifier and bounding boxes for every ray.
        compound = TopoDS_Compound()
        builder = BRep_Builder()
        builder.MakeCompound(compound)
        for partner in partners:
            builder.Add(compound, partner)
        self.faces = IntCurvesFace_ShapeIntersector()
        self.faces.Load(compound, CONFUSION)

    def nearest(self, origin: gp_Pnt, direction: gp_Dir) -> float | None:
        self.faces.Perform(gp_Lin(origin, direction), CONFUSION, self.reach)
        if not self.faces.IsDone():
            return None
        return self._first([self.faces.WParameter(k) for k in range(1, self.faces.NbPnt() + 1)])

    def nearest_surface(self, origin: gp_Pnt, direction: gp_Dir) -> float | None:
        ray = Geom_Line(origin, direction)
        hits = []
        for surface in self.surfaces:
            inter = GeomAPI_IntCS(ray, surface)
            if inter.IsDone():
                # Signed along the ray: hits behind the origin are not across the wall.
                hits.extend(gp_Vec(origin, inter.Point(k)).Dot(gp_Vec(direction)) for k in range(1, inter.NbPoints() + 1))
        return self._first(hits)

    def _first(self, hits: list[float]) -> float | None:
        ahead = [w for w in hits if CONFUSION < w <= self.reach]
        return min(ahead) if ahead else None


def _mid_points(face: TopoDS_Face, rays: _Rays) -> list[tuple[float, float, gp_Pnt, float]]:
    """(u, v, the mid-wall point across, the wall's thickness there) at area samples of `face` whose inward
    ray meets a partner: what the moved face is checked against."""
    normals = OutwardNormals(face)
    out = []
    size = diagonal(face)
    for _, u, v in area_samples(face, size, size / MID_WALL_CHECKS):
        sample = normals.at(u, v)
        if sample is None:
            continue
        point, normal = gp_Pnt(*sample[0]), gp_Vec(*sample[1]).Reversed()
        across = rays.nearest(point, gp_Dir(normal))
        if across is not None:
            out.append((u, v, point.Translated(normal * (0.5 * across)), across))
    return out


def _move_poles(spline: Geom_BSplineSurface, inward: float, rays: _Rays) -> bool:
    """Moves each pole along the inward normal at its Greville point by half the distance there to the nearest
    partner face, or past them to the nearest partner surface; a pole whose ray meets neither takes the step of
    the nearest pole that did. False when no ray meets."""
    us = _greville(_values(spline.UKnotSequence()), spline.UDegree(), spline.NbUPoles())
    vs = _greville(_values(spline.VKnotSequence()), spline.VDegree(), spline.NbVPoles())
    props = GeomLProp_SLProps(spline, 1, NORMAL_RESOLUTION)
    directions: dict[tuple[int, int], gp_Vec] = {}
    found: dict[tuple[int, int], float] = {}
    for i, u in enumerate(us, start=1):
        for j, v in enumerate(vs, start=1):
            props.SetParameters(u, v)
            if not props.IsNormalDefined():
                continue
            directions[(i, j)] = gp_Vec(props.Normal()) * inward
            point, direction = props.Value(), gp_Dir(directions[(i, j)])
            across = rays.nearest(point, direction)
            if across is None:
                across = rays.nearest_surface(point, direction)
            if across is not None:
                found[(i, j)] = 0.5 * across
    if not found:
        return False
    moves = []
    for (i, j), direction in directions.items():
        step = found.get((i, j))
        if step is None:
            step = found[min(found, key=lambda k: ((k[0] - i) ** 2 + (k[1] - j) ** 2, k))]
        moves.append((i, j, spline.Pole(i, j).Translated(direction * step)))
    for i, j, pole in moves:
        spline.SetPole(i, j, pole)
    return True


def _room(surface, bounds: tuple[float, float, float, float], margin: float) -> tuple[float, float, float, float]:
    """The part of `surface` the moved face is made on: all of a bounded surface (a B-spline's own extent past
    the face is the room its joints grow into, as an offset of it has), and a plane's face's parameter box (in
    mm) widened by `margin` each way."""
    if all(abs(b) < INFINITE_PARAMETER for b in surface.Bounds()):
        return surface.Bounds()
    u0, u1, v0, v1 = bounds
    return (u0 - margin, u1 + margin, v0 - margin, v1 + margin)


def _within(face: tuple[float, ...], surface: tuple[float, ...]) -> tuple[float, float, float, float]:
    """The face's parameter box clamped to its surface's: a boundary's tolerance can reach past the surface."""
    return (max(face[0], surface[0]), min(face[1], surface[1]), max(face[2], surface[2]), min(face[3], surface[3]))


def _refine(spline: Geom_BSplineSurface, bounds: tuple[float, float, float, float], spans: int) -> None:
    """Raises the degree to MID_WALL_DEGREE and inserts knots until the face's range holds `spans` spans each
    way, so that the moved poles can follow a thickness that varies across a face whose own surface is simple (a
    plane's B-spline form has four poles)."""
    spline.IncreaseDegree(max(spline.UDegree(), MID_WALL_DEGREE), max(spline.VDegree(), MID_WALL_DEGREE))
    u0, u1, v0, v1 = bounds
    for lo, hi, knots, insert in (
        (u0, u1, spline.UKnots, spline.InsertUKnot),
        (v0, v1, spline.VKnots, spline.InsertVKnot),
    ):
        inside = [k for k in _values(knots()) if lo < k < hi]
        if len(inside) + 1 >= spans:
            continue
        for n in range(1, spans):
            insert(lo + (hi - lo) * n / spans, 1, CONFUSION, True)


def _values(array) -> list[float]:
    """The values of an OCCT array of reals (TColStd_Array1OfReal)."""
    return [array.Value(k) for k in range(array.Lower(), array.Upper() + 1)]


def _greville(flat: list[float], degree: int, poles: int) -> list[float]:
    return [sum(flat[i + 1 : i + 1 + degree]) / degree for i in range(poles)]


def _face_on(spline: Geom_BSplineSurface, face: TopoDS_Face) -> TopoDS_Face | None:
    """A face on `spline` bounded by `face`'s wires, each edge rebuilt from its curve in the face's parameters
    (the same on `spline`), with `face`'s orientation."""
    forward = TopoDS.Face(face.Oriented(TopAbs_FORWARD))
    outer = BRepTools.OuterWire_s(forward)
    wires = []
    explorer = TopExp_Explorer(forward, TopAbs_WIRE)
    while explorer.More():
        wire = TopoDS.Wire(explorer.Current())
        explorer.Next()
        maker = BRepBuilderAPI_MakeWire()
        edges = BRepTools_WireExplorer(wire, forward)
        rebuilt = 0
        while edges.More():
            edge = edges.Current()
            edges.Next()
            # The pcurve as the forward face holds the edge (a seam's two differ by orientation).
            curve = BRep_Tool.CurveOnSurface_s(edge, forward, 0.0, 0.0)
            span = BRepAdaptor_Curve2d(edge, forward)
            if curve is None:
                return None
            new = BRepBuilderAPI_MakeEdge(curve, spline, span.FirstParameter(), span.LastParameter()).Edge()
            BRepLib.BuildCurves3d_s(new)
            maker.Add(TopoDS.Edge(new.Oriented(edge.Orientation())))
            rebuilt += 1
        # BRepTools_WireExplorer skips the edges of a wire it cannot chain (a gap, a non-manifold vertex).
        if not maker.IsDone() or rebuilt != len(subshapes(wire, TopAbs_EDGE)):
            return None
        wires.append((wire.IsSame(outer), maker.Wire()))
    wires.sort(key=lambda w: not w[0])
    if not wires or not wires[0][0]:
        return None
    builder = BRepBuilderAPI_MakeFace(spline, wires[0][1], True)
    for _, wire in wires[1:]:
        builder.Add(wire)
    if not builder.IsDone():
        return None
    fix = ShapeFix_Face(builder.Face())
    fix.Perform()
    return TopoDS.Face(fix.Face().Oriented(face.Orientation()))
