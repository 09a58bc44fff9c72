"""`probe_edges`: what lies beyond the free edges of mid-patches, measured for Rust's joint decisions.

For each free edge (an edge of one face of the fused patches) the edge is sampled at evenly spaced
parameters, both ends included. At each sample: the point, the face's normal, the outward direction (in the
face's tangent plane, at right angles to the edge, away from the face), and where a ray along the outward
direction meets the support surfaces of the target faces. (Whether the edge lies in the material is Rust's
test, on the solid's mesh: the kernel's solid classifier is far too slow for thousands of points.)
"""

import functools
from dataclasses import dataclass
from typing import Any

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.Bnd import Bnd_Box
from OCP.BRepTools import BRepTools
from OCP.Geom import (
    Geom_BSplineSurface,
    Geom_Line,
    Geom_OffsetSurface,
    Geom_RectangularTrimmedSurface,
    Geom_Surface,
    Geom_SurfaceOfLinearExtrusion,
)
from OCP.GeomAbs import GeomAbs_C1, GeomAbs_C2
from OCP.GeomConvert import GeomConvert, GeomConvert_ApproxSurface
from OCP.GeomAPI import GeomAPI_IntCS
from OCP.GeomAdaptor import GeomAdaptor_Curve, GeomAdaptor_Surface
from OCP.gp import gp_Dir, gp_Lin, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.IntCurveSurface import (
    IntCurveSurface_HInter,
    IntCurveSurface_ThePolygonOfHInter,
    IntCurveSurface_ThePolyhedronOfHInter,
)
from OCP.GCPnts import GCPnts_QuasiUniformDeflection
from OCP.IntTools import IntTools_FClass2d
from OCP.Intf import Intf_Tool
from OCP.collections import Array1_double
from OCP.Adaptor3d import Adaptor3d_HSurfaceTool
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FORWARD, TopAbs_IN, TopAbs_OUT, TopAbs_REVERSED, TopAbs_State, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Wire

from ..constants import (
    GAP_DEFLECTION_RATIO,
    HULL_DIRECTIONS,
    HULL_MARGIN,
    POLYGON_MIN_LENGTH,
    POLYHEDRON_MAX_POINTS,
    POLYHEDRON_MIN_SAMPLES,
    RAY_APPROX_RATIO,
    RAY_MEET_ITERATIONS,
    RAY_MEET_RESIDUAL,
    SIDE_STEP_RATIO,
    SIDE_STEP_TOLERANCES,
    SINGULAR_METRIC,
    SINGULAR_NUDGES,
)
from ..geom.topology import diagonal, distance_to, indexed_map
from ..geom.vectors import Vec, add_scaled, cross, dot, norm, scale, sub, xyz
from ..protocol.errors import BadArgs, KernelError


# A point's parameters on a surface.
UV = tuple[float, float]


@dataclass(frozen=True)
class EdgeSample:
    point: Vec
    normal: Vec
    outward: Vec


class FaceSides:
    """One face's boundary, walked once for all of its edges: the oriented edges by shape, and per wire a 2D
    classifier of the face bounded by its outer wire and that wire alone, built on first use. Which side of
    an edge the face lies on is a matter of the edge's own wire; the whole face's classifier walks every wire,
    so probing a face with n holes cost n^2 (5.8 s of a 900-hole plate's 13 s)."""

    def __init__(self, face: TopoDS_Face) -> None:
        self.face = face
        # Per shape hash, each edge as the face's boundary runs through it (wires and edges explored from the
        # face compose its orientation, in the face's order) with the index of its wire.
        self._edges: dict[int, list[tuple[TopoDS_Edge, int]]] = {}
        # The wires as the forward face holds them, for the classifiers.
        self._wires: list[TopoDS_Wire] = []
        wires = TopExp_Explorer(face, TopAbs_WIRE)
        while wires.More():
            wire = wires.Current()
            edges = TopExp_Explorer(wire, TopAbs_EDGE)
            while edges.More():
                edge = TopoDS.Edge(edges.Current())
                self._edges.setdefault(hash(edge), []).append((edge, len(self._wires)))
                edges.Next()
            self._wires.append(TopoDS.Wire(wire.Composed(face.Orientation())))
            wires.Next()
        self._forward = TopoDS.Face(face.Oriented(TopAbs_FORWARD))
        self._outer = BRepTools.OuterWire_s(self._forward)
        self._classifiers: dict[int, IntTools_FClass2d] = {}
        # Bounded by the face's (u, v) range, which takes a walk of every edge's pcurve to find.
        self.surface = BRepAdaptor_Surface(face, True)
        self.tolerance = BRep_Tool.Tolerance_s(face)
        self.side_step = max(SIDE_STEP_RATIO * diagonal(face), SIDE_STEP_TOLERANCES * self.tolerance)

    def oriented_edge(self, edge: TopoDS_Shape) -> TopoDS_Edge:
        """The edge as the face's boundary runs through it (orientation composed with the face's): the first
        use in the face's order, as a seam is used twice."""
        return self._find(edge)[0]

    def _find(self, edge: TopoDS_Shape) -> tuple[TopoDS_Edge, int]:
        for candidate in self._edges.get(hash(edge), []):
            if candidate[0].IsSame(edge):
                return candidate
        raise BadArgs("the edge is not an edge of the face")

    def state(self, edge: TopoDS_Shape, u: float, v: float) -> TopAbs_State:
        """IN, OUT or ON the face near `edge` at (u, v), by the face's outer wire and the edge's wire.
        IntTools_FClass2d tests polygons of the wires and falls back to the exact classifier within their sag
        of them, so it answers as BRepClass_FaceClassifier does away from the other wires."""
        index = self._find(edge)[1]
        if index not in self._classifiers:
            bounded = TopoDS.Face(self._forward.EmptyCopied())
            builder = BRep_Builder()
            builder.Add(bounded, self._outer)
            if not self._wires[index].IsSame(self._outer):
                builder.Add(bounded, self._wires[index])
            self._classifiers[index] = IntTools_FClass2d(bounded, self.tolerance)
        return self._classifiers[index].Perform(gp_Pnt2d(u, v))


def sample_edge(face: TopoDS_Face, edge: TopoDS_Shape, samples: int, sides: FaceSides | None = None) -> list[EdgeSample]:
    """Samples at evenly spaced parameters of the edge's curve, in the curve's direction. `sides`: the face's
    boundary when several of its edges are sampled."""
    if samples < 2:
        raise BadArgs("at least 2 samples per edge")
    sides = sides or FaceSides(face)
    oriented = sides.oriented_edge(edge)
    if BRep_Tool.Degenerated_s(oriented):
        raise BadArgs("a degenerated edge has no outward direction")
    curve = BRepAdaptor_Curve(oriented)
    curve2d = BRepAdaptor_Curve2d(oriented, face)
    surface = sides.surface
    reversed_edge = oriented.Orientation() == TopAbs_REVERSED
    reversed_face = face.Orientation() == TopAbs_REVERSED
    first, last = curve.FirstParameter(), curve.LastParameter()
    centre = 0.5 * (first + last)

    def frame(s: float) -> tuple[gp_Pnt, Vec, Any, Vec, Vec, Vec] | None:
        """Point, tangent, uv and the surface's derivatives at curve parameter s; None at a singular point."""
        point, tangent = gp_Pnt(), gp_Vec()
        sp, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
        try:
            curve.D1(s, point, tangent)
            uv = curve2d.Value(s)
            surface.D1(uv.X(), uv.Y(), sp, su, sv)
        except Exception:  # OCCT's Standard_Failure types: an offset surface's undefined normal, a pole
            return None
        normal, t = cross(xyz(su), xyz(sv)), xyz(tangent)
        if norm(normal) == 0.0 or norm(t) == 0.0:
            return None
        return point, t, uv, normal, xyz(su), xyz(sv)

    out = []
    middle = None
    for k in range(samples):
        s = first + (last - first) * k / (samples - 1)
        # A singular point (the pole of a face narrowing to a point, where an offset surface has no normal) is
        # stepped past, toward the middle of the edge, by a little of its length.
        at = next((f for f in (frame(s + (centre - s) * nudge) for nudge in SINGULAR_NUDGES) if f), None)
        if at is None:
            raise KernelError(f"edge sample {k}: zero tangent or normal (a singular point)")
        point, t, uv, normal, su_v, sv_v = at
        normal = scale(normal, (-1.0 if reversed_face else 1.0) / norm(normal))
        t = scale(t, (-1.0 if reversed_edge else 1.0) / norm(t))
        # The face lies to the left of its boundary run (looking down the normal): outward is to the right.
        outward = cross(t, normal)
        outward = scale(outward, 1.0 / norm(outward))
        out.append(EdgeSample(xyz(point), normal, outward))
        if k == samples // 2:
            middle = ((uv.X(), uv.Y()), su_v, sv_v)
    if _runs_backwards(sides, edge, out[samples // 2], middle):
        out = [EdgeSample(s.point, s.normal, scale(s.outward, -1.0)) for s in out]
    return out


def _runs_backwards(
    sides: FaceSides, edge: TopoDS_Shape, sample: EdgeSample, at: tuple[tuple[float, float], Vec, Vec]
) -> bool:
    """Guards the orientation rule: whether a point a little inward of the middle sample is off the face and
    one a little outward on it (the rule got the side wrong). `at`: the sample's (u, v) and the surface's
    derivatives there, which turn the step along `outward` into a step in (u, v)."""
    (u, v), su, sv = at
    du, dv = _uv_step(su, sv, scale(sample.outward, sides.side_step))
    state_in = sides.state(edge, u - du, v - dv)
    state_out = sides.state(edge, u + du, v + dv)
    return state_in == TopAbs_OUT and state_out == TopAbs_IN


def _uv_step(su: Vec, sv: Vec, step: Vec) -> tuple[float, float]:
    """The (du, dv) whose image su du + sv dv is nearest `step` (least squares on the first fundamental form)."""
    e, f, g = dot(su, su), dot(su, sv), dot(sv, sv)
    a, b = dot(su, step), dot(sv, step)
    det = e * g - f * f
    if det <= 0.0:
        raise KernelError("edge sample: singular surface metric")
    return (g * a - f * b) / det, (e * b - f * a) / det


class PoleHull:
    """A B-spline surface lies in the convex hull of its poles (positive weights), so a ray segment that keeps
    clear of the hull meets nothing. GeomAPI_IntCS takes 0.1 to 1 ms to find that a ray misses a spline; most rays
    of an edge miss most of the splines near it. The test: the poles all before the ray's start or beyond its
    reach, or all on one side of one of HULL_DIRECTIONS planes through the ray (a polygon around the ray)."""

    def __init__(self, surface: Geom_BSplineSurface, margin: float) -> None:
        import numpy  # only for parts with splines: it costs a small part's start-up 0.1 s

        poles = [
            xyz(surface.Pole(i, j)) for i in range(1, surface.NbUPoles() + 1) for j in range(1, surface.NbVPoles() + 1)
        ]
        self.poles = numpy.array(poles)
        angles = numpy.arange(HULL_DIRECTIONS) * (numpy.pi / HULL_DIRECTIONS)
        self.around = numpy.stack([numpy.cos(angles), numpy.sin(angles)])
        self.margin = margin

    def misses(self, origin: Vec, direction: Vec, reach: float) -> bool:
        start, d, across_ray = _ray_frame(origin, direction)
        relative = self.poles - start
        along = relative @ d
        if along.max() < -self.margin or along.min() > reach + self.margin:
            return True
        across = (relative @ across_ray) @ self.around
        return bool((across.min(axis=0) > self.margin).any() or (across.max(axis=0) < -self.margin).any())


@functools.lru_cache(maxsize=1)
def _ray_frame(origin: Vec, direction: Vec):
    """The ray's start and direction as arrays, and two unit vectors across it (columns): computed once per ray,
    not once per spline it is tested against."""
    import numpy

    d = numpy.array(direction)
    helper = numpy.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else numpy.array([0.0, 1.0, 0.0])
    e1 = numpy.cross(d, helper)
    e1 /= numpy.linalg.norm(e1)
    return numpy.array(origin), d, numpy.stack([e1, numpy.cross(d, e1)], axis=1)


class SampledSpline:
    """A B-spline surface with the polyhedra GeomAPI_IntCS samples it into for a line, made once. IntCS samples
    the surface again for every line: each span between C2 breaks (the knots of an approximation of degree 9),
    at least 20 x 20 points (up to 15 ms a ray on the offset patches of a freeform part), and an edge's rays all
    meet the same few surfaces. The rest is IntCS's own way with a line (IntCurveSurface_Inter): the line
    clipped to each polyhedron's box, and the meetings of the clipped segment with it refined on the surface."""

    def __init__(self, spline: Geom_BSplineSurface, counts: list[tuple[float, float, int, float, float, int]]):
        # Each span with its own bounds, as IntCS bounds a meeting's refinement to the span it was found in.
        self.spans = []
        for u1, u2, nu, v1, v2, nv in counts:
            span = GeomAdaptor_Surface(spline, u1, u2, v1, v2)
            self.spans.append((span, IntCurveSurface_ThePolyhedronOfHInter(span, nu, nv, u1, v1, u2, v2)))

    @classmethod
    def of(cls, spline: Geom_BSplineSurface) -> "SampledSpline | None":
        """The spline sampled, or None when its samples would pass POLYHEDRON_MAX_POINTS (they are kept for the
        whole probe: a spline of thousands of spans is met by IntCS ray by ray instead)."""
        whole = GeomAdaptor_Surface(spline)
        us, vs = cls._breaks(whole, True), cls._breaks(whole, False)
        counts = []
        for u1, u2 in zip(us, us[1:]):
            nu = max(Adaptor3d_HSurfaceTool.NbSamplesU_s(whole, u1, u2), POLYHEDRON_MIN_SAMPLES)
            for v1, v2 in zip(vs, vs[1:]):
                nv = max(Adaptor3d_HSurfaceTool.NbSamplesV_s(whole, v1, v2), POLYHEDRON_MIN_SAMPLES)
                counts.append((u1, u2, nu, v1, v2, nv))
        if sum(nu * nv for _, _, nu, _, _, nv in counts) > POLYHEDRON_MAX_POINTS:
            return None
        return cls(spline, counts)

    @staticmethod
    def _breaks(adaptor: GeomAdaptor_Surface, along_u: bool) -> list[float]:
        count = adaptor.NbUIntervals(GeomAbs_C2) if along_u else adaptor.NbVIntervals(GeomAbs_C2)
        breaks = Array1_double(1, count + 1)
        (adaptor.UIntervals if along_u else adaptor.VIntervals)(breaks, GeomAbs_C2)
        return [breaks.Value(k) for k in range(1, count + 2)]

    def meet(self, line: Geom_Line) -> list[tuple[float, float, float, Vec]]:
        """(u, v, w along the line, point) of each meeting of the whole line."""
        curve = GeomAdaptor_Curve(line)
        found = []
        for span, polyhedron in self.spans:
            clip = Intf_Tool()
            clip.LinBox(line.Lin(), polyhedron.Bounding(), Bnd_Box())
            for k in range(1, clip.NbSegments() + 1):
                start, end = clip.BeginParam(k), clip.EndParam(k)
                if end - start < POLYGON_MIN_LENGTH:
                    start, end = start - POLYGON_MIN_LENGTH, end + POLYGON_MIN_LENGTH
                intersector = IntCurveSurface_HInter()
                polygon = IntCurveSurface_ThePolygonOfHInter(curve, start, end, 2)
                intersector.Perform(curve, polygon, span, polyhedron)
                for j in range(1, intersector.NbPoints() + 1):
                    meeting = intersector.Point(j)
                    found.append((meeting.U(), meeting.V(), meeting.W(), xyz(meeting.Pnt())))
        return found


class RaySurface:
    """A target face's support surface, in the form rays meet fastest (see `meetings`)."""

    def __init__(self, face: TopoDS_Face, reach: float) -> None:
        self.exact = BRep_Tool.Surface_s(face)
        self.locator: Geom_Surface | None = None
        # Whether the meetings' (u, v) are the face's own parameters (not those of a spline standing for it).
        self.own_parameters = not isinstance(self.exact, Geom_SurfaceOfLinearExtrusion)
        if isinstance(self.exact, Geom_SurfaceOfLinearExtrusion):
            # A spline swept along a line (a strip grown from a curved patch's edge) is exactly a spline of degree
            # 1 across, which GeomAPI_IntCS meets eight times faster. Meetings beyond `reach` of the face are of
            # no use to the joints.
            curve = self.exact.BasisCurve()
            _, _, v0, v1 = BRepTools.UVBounds_s(face)
            bounded = Geom_RectangularTrimmedSurface(
                self.exact, curve.FirstParameter(), curve.LastParameter(), v0 - reach, v1 + reach
            )
            self.exact = GeomConvert.SurfaceToBSplineSurface_s(bounded)
        elif isinstance(self.exact, Geom_OffsetSurface) and isinstance(self.exact.BasisSurface(), Geom_BSplineSurface):
            approx = GeomConvert_ApproxSurface(
                self.exact, RAY_APPROX_RATIO * reach, GeomAbs_C1, GeomAbs_C1, 9, 9, 100, 1
            )
            if approx.IsDone() and approx.HasResult():
                self.locator = approx.Surface()
        spline = self.locator or self.exact
        self.hull: PoleHull | None = None
        self.sampled: SampledSpline | None = None
        if isinstance(spline, Geom_BSplineSurface):
            # The exact surface lies within twice the approximation's tolerance of its locator.
            margin = HULL_MARGIN + (2.0 * RAY_APPROX_RATIO * reach if self.locator is not None else 0.0)
            self.hull = PoleHull(spline, margin)
            self.sampled = SampledSpline.of(spline)

    def meetings(self, line: Geom_Line, origin: Vec, direction: Vec, reach: float) -> list[tuple[Vec, UV | None]]:
        """Points where the ray's line meets the surface, all of them or at least those within (0, reach] along
        the ray, each with its (u, v) on the face's surface (None when the meeting was found on a spline standing
        for it): none when the ray keeps clear of the spline's pole hull; on a spline, through its sampling made
        once (SampledSpline); on the locator (same parameters as the exact surface), each settled on the exact
        surface; on the exact surface alone (GeomAPI_IntCS) if it is no spline, or a meeting fails to settle."""
        if self.hull is not None and self.hull.misses(origin, direction, reach):
            return []
        own = self.own_parameters
        if self.sampled is not None:
            met = self.sampled.meet(line)
            if self.locator is None:
                return [(point, (u, v) if own else None) for u, v, _, point in met]
            settled = [self._settle(u, v, w, origin, direction) for u, v, w, _ in met]
            if all(s is not None for s in settled):
                return settled
        meet = GeomAPI_IntCS(line, self.exact)
        if not meet.IsDone():
            return []
        found = []
        for k in range(1, meet.NbPoints() + 1):
            u, v, _ = meet.Parameters(k)
            found.append((xyz(meet.Point(k)), (u, v) if own else None))
        return found

    def _settle(self, u: float, v: float, w: float, origin: Vec, direction: Vec) -> tuple[Vec, UV] | None:
        """Newton's method on S(u, v) - (origin + w direction) = 0 from a located meeting: the point and its
        (u, v)."""
        point, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
        for _ in range(RAY_MEET_ITERATIONS):
            try:
                self.exact.D1(u, v, point, su, sv)
            except Exception:  # an offset surface has no normal at its basis's singular points
                return None
            residual = sub(xyz(point), add_scaled(origin, direction, w))
            if norm(residual) <= RAY_MEET_RESIDUAL:
                return xyz(point), (u, v)
            a, b, c = xyz(su), xyz(sv), scale(direction, -1.0)
            det = dot(a, cross(b, c))
            if abs(det) <= SINGULAR_METRIC:
                return None
            # Cramer's rule for a du + b dv + c dw = -residual.
            rhs = scale(residual, -1.0)
            u += dot(rhs, cross(b, c)) / det
            v += dot(a, cross(rhs, c)) / det
            w += dot(a, cross(b, rhs)) / det
        return None


class FaceEdges:
    """A target face's edges, to measure how far a point off the face is from it (the distance to its nearest
    edge: a point of the support surface off the face is nearest the face on its boundary). Polylines within
    `deflection` of the edges find the edges that can be nearest, and the distance is measured exactly to those
    alone: measured to the whole face (BRepExtrema), it took a millisecond a meeting, and nine meetings in ten
    lie off their face. When an edge cannot be sampled, the distance is measured to the whole face."""

    def __init__(self, face: TopoDS_Face, deflection: float) -> None:
        import numpy  # only for parts with free edges that meet faces

        self.face = face
        self.deflection = deflection
        self.edges: list[TopoDS_Edge] = []
        starts, ends, owners = [], [], []
        # Each edge once (a seam bounds its face twice).
        unique = indexed_map(face, TopAbs_EDGE)
        for k in range(1, unique.Size() + 1):
            edge = TopoDS.Edge(unique.FindKey(k))
            if BRep_Tool.Degenerated_s(edge):
                continue
            points = GCPnts_QuasiUniformDeflection(BRepAdaptor_Curve(edge), deflection)
            if not points.IsDone() or points.NbPoints() < 2:
                self.edges = []
                break
            polyline = [xyz(points.Value(j)) for j in range(1, points.NbPoints() + 1)]
            starts.extend(polyline[:-1])
            ends.extend(polyline[1:])
            owners.extend([len(self.edges)] * (len(polyline) - 1))
            self.edges.append(edge)
        self.starts = numpy.array(starts).reshape(-1, 3)
        self.spans = numpy.array(ends).reshape(-1, 3) - self.starts
        lengths = (self.spans * self.spans).sum(axis=1)
        self.lengths = numpy.where(lengths > 0.0, lengths, 1.0)
        self.owners = numpy.array(owners, dtype=int)

    def distance(self, point: Vec) -> float:
        """From `point`, a point of the face's support surface off the face, to the face."""
        import numpy

        if not self.edges:
            return _distance(point, self.face)
        relative = numpy.array(point) - self.starts
        along = numpy.clip((relative * self.spans).sum(axis=1) / self.lengths, 0.0, 1.0)
        off = relative - along[:, None] * self.spans
        near = numpy.sqrt((off * off).sum(axis=1))
        # An edge lies within `deflection` of its polyline: only the edges whose polylines come within twice that
        # of the nearest can hold the nearest point.
        candidates = sorted(set(self.owners[near <= near.min() + 2.0 * self.deflection].tolist()))
        return min(_distance(point, self.edges[k]) for k in candidates)


class TargetFaces:
    """Faces rays may meet: their support surfaces, boxes (for a quick miss), classifiers and edges."""

    def __init__(self, faces: dict[int, TopoDS_Face], reach: float) -> None:
        self.faces = faces
        self.surfaces = {i: RaySurface(f, reach) for i, f in faces.items()}
        self.deflection = GAP_DEFLECTION_RATIO * reach
        self._edges: dict[int, FaceEdges] = {}
        self._classifiers: dict[int, IntTools_FClass2d] = {}
        # Boxes grown by the reach once, not per ray.
        self.boxes = {}
        for i, f in faces.items():
            box = Bnd_Box()
            BRepBndLib.Add_s(f, box, False)
            box.Enlarge(reach)
            self.boxes[i] = box

    def near(self, samples: list[EdgeSample], reach: float, skip: set[int]) -> list[int]:
        """Targets whose grown boxes meet the box of all the edge's rays: the only ones its rays can meet."""
        rays = Bnd_Box()
        for s in samples:
            rays.Add(gp_Pnt(*s.point))
            rays.Add(gp_Pnt(*add_scaled(s.point, s.outward, reach)))
        return [i for i in self.faces if i not in skip and not self.boxes[i].IsOut(rays)]

    def hits(self, origin: Vec, direction: Vec, reach: float, candidates: list[int]) -> list[dict[str, Any]]:
        """Meetings of the ray with the support surfaces of `candidates` within (0, reach]: face, distance along
        the ray and gap (distance from the meeting point to the face itself, 0 on the face). Nearest first."""
        end = add_scaled(origin, direction, reach)
        ray_box = Bnd_Box()
        ray_box.Add(gp_Pnt(*origin))
        ray_box.Add(gp_Pnt(*end))
        line = Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction)))
        found = []
        for i in candidates:
            face = self.faces[i]
            if self.boxes[i].IsOut(ray_box):
                continue
            for p, uv in self.surfaces[i].meetings(line, origin, direction, reach):
                distance = dot(sub(p, origin), direction)
                if 0.0 < distance <= reach:
                    found.append({"face": i, "distance": distance, "gap": self._gap(i, face, p, uv)})
        found.sort(key=lambda h: (h["distance"], h["face"]))
        return found

    def _gap(self, i: int, face: TopoDS_Face, point: Vec, uv: UV | None) -> float:
        """The meeting's distance to face i, 0 on it. Whether it is on the face is told from its own (u, v) where
        known (IntTools_FClass2d, made once per face): from the 3D point, BRepClass_FaceClassifier projects it
        within the face's parameter range, so a meeting on the far side of a cylinder, torus or offset surface
        whose opposite point is on the face read as on it."""
        if uv is not None:
            if i not in self._classifiers:
                forward = TopoDS.Face(face.Oriented(TopAbs_FORWARD))
                self._classifiers[i] = IntTools_FClass2d(forward, BRep_Tool.Tolerance_s(face))
            inside = self._classifiers[i].Perform(gp_Pnt2d(*uv)) == TopAbs_IN
        else:
            tolerance = BRep_Tool.Tolerance_s(face)
            inside = BRepClass_FaceClassifier(face, gp_Pnt(*point), tolerance).State() == TopAbs_IN
        if inside:
            return 0.0
        if i not in self._edges:
            self._edges[i] = FaceEdges(face, self.deflection)
        return self._edges[i].distance(point)


def _distance(point: Vec, shape: TopoDS_Shape) -> float:
    """`distance_to`, an error when OCCT cannot tell (a gap must be known)."""
    distance = distance_to(gp_Pnt(*point), shape)
    if distance is None:
        raise KernelError("point-to-face distance failed")
    return distance


def probe(edges: list[tuple[TopoDS_Face, TopoDS_Shape, int]], targets: TargetFaces, samples: int, reach: float) -> list[dict[str, Any]]:
    """`edges`: (face, edge, own face index). One reply entry per edge."""
    out = []
    sides: dict[int, FaceSides] = {}
    for face, edge, own in edges:
        entry: dict[str, list[Any]] = {"points": [], "normals": [], "outward": [], "hits": []}
        if own not in sides:
            sides[own] = FaceSides(face)
        sampled = sample_edge(face, edge, samples, sides[own])
        candidates = targets.near(sampled, reach, {own})
        for sample in sampled:
            entry["points"].append(list(sample.point))
            entry["normals"].append(list(sample.normal))
            entry["outward"].append(list(sample.outward))
            entry["hits"].append(targets.hits(sample.point, sample.outward, reach, candidates))
        out.append(entry)
    return out
