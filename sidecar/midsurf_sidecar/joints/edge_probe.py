"""`probe_edges`: what lies beyond the free edges of mid-patches, measured for Rust's joint decisions.

For each free edge (an edge of one face of the fused patches) the edge is sampled at evenly spaced
parameters, both ends included. At each sample: the point, the face's normal, the outward direction (in the
face's tangent plane, at right angles to the edge, away from the face), and where a ray along the outward
direction meets the support surfaces of the target faces. (Whether the edge lies in the material is Rust's
test, on the solid's mesh: the kernel's solid classifier is far too slow for thousands of points.)
"""

from dataclasses import dataclass
from typing import Any

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.Bnd import Bnd_Box
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_Line, Geom_RectangularTrimmedSurface, Geom_Surface, Geom_SurfaceOfLinearExtrusion
from OCP.GeomConvert import GeomConvert
from OCP.GeomAPI import GeomAPI_IntCS
from OCP.gp import gp_Dir, gp_Lin, gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_EDGE, TopAbs_IN, TopAbs_OUT, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape

from ..constants import SIDE_STEP_RATIO, SIDE_STEP_TOLERANCES
from ..geom.topology import diagonal
from ..geom.vectors import Vec, add_scaled, cross, dot, norm, scale, sub, xyz
from ..protocol.errors import BadArgs, KernelError


@dataclass(frozen=True)
class EdgeSample:
    point: Vec
    normal: Vec
    outward: Vec


def oriented_edge(face: TopoDS_Face, edge: TopoDS_Shape) -> TopoDS_Edge:
    """The edge as the face's boundary runs through it (orientation composed with the face's)."""
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        if explorer.Current().IsSame(edge):
            return TopoDS.Edge(explorer.Current())
        explorer.Next()
    raise BadArgs("the edge is not an edge of the face")


def sample_edge(face: TopoDS_Face, edge: TopoDS_Shape, samples: int) -> list[EdgeSample]:
    """Samples at evenly spaced parameters of the edge's curve, in the curve's direction."""
    if samples < 2:
        raise BadArgs("at least 2 samples per edge")
    oriented = oriented_edge(face, edge)
    if BRep_Tool.Degenerated_s(oriented):
        raise BadArgs("a degenerated edge has no outward direction")
    curve = BRepAdaptor_Curve(oriented)
    curve2d = BRepAdaptor_Curve2d(oriented, face)
    surface = BRepAdaptor_Surface(face, True)
    reversed_edge = oriented.Orientation() == TopAbs_REVERSED
    reversed_face = face.Orientation() == TopAbs_REVERSED
    first, last = curve.FirstParameter(), curve.LastParameter()
    out = []
    for k in range(samples):
        s = first + (last - first) * k / (samples - 1)
        point, tangent = gp_Pnt(), gp_Vec()
        curve.D1(s, point, tangent)
        uv = curve2d.Value(s)
        sp, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
        surface.D1(uv.X(), uv.Y(), sp, su, sv)
        normal = cross(xyz(su), xyz(sv))
        t = xyz(tangent)
        if norm(normal) == 0.0 or norm(t) == 0.0:
            raise KernelError(f"edge sample {k}: zero tangent or normal (a singular point)")
        normal = scale(normal, (-1.0 if reversed_face else 1.0) / norm(normal))
        t = scale(t, (-1.0 if reversed_edge else 1.0) / norm(t))
        # The face lies to the left of its boundary run (looking down the normal): outward is to the right.
        outward = cross(t, normal)
        outward = scale(outward, 1.0 / norm(outward))
        out.append(EdgeSample(xyz(point), normal, outward))
    if _runs_backwards(face, out):
        out = [EdgeSample(s.point, s.normal, scale(s.outward, -1.0)) for s in out]
    return out


def _runs_backwards(face: TopoDS_Face, samples: list[EdgeSample]) -> bool:
    """Guards the orientation rule: whether a point a little inward of the middle sample is off the face and
    one a little outward on it (the rule got the side wrong)."""
    middle = samples[len(samples) // 2]
    tolerance = BRep_Tool.Tolerance_s(face)
    step = max(SIDE_STEP_RATIO * diagonal(face), SIDE_STEP_TOLERANCES * tolerance)
    inner = add_scaled(middle.point, middle.outward, -step)
    outer = add_scaled(middle.point, middle.outward, step)
    state_in = BRepClass_FaceClassifier(face, gp_Pnt(*inner), tolerance).State()
    state_out = BRepClass_FaceClassifier(face, gp_Pnt(*outer), tolerance).State()
    return state_in == TopAbs_OUT and state_out == TopAbs_IN


def _intersectable(face: TopoDS_Face, reach: float) -> Geom_Surface:
    """The face's support surface in the form rays meet fastest, over the face grown by `reach`.

    A surface of linear extrusion of a spline (a strip grown from a curved patch's edge) costs GeomAPI_IntCS
    about 2 ms a ray, eight times its exact B-spline form (a spline curve swept along a line is a spline of
    degree 1 across), so it is converted once. Meetings beyond `reach` of the face are of no use to the joints.
    """
    surface = BRep_Tool.Surface_s(face)
    if not isinstance(surface, Geom_SurfaceOfLinearExtrusion):
        return surface
    curve = surface.BasisCurve()
    _, _, v0, v1 = BRepTools.UVBounds_s(face)
    bounded = Geom_RectangularTrimmedSurface(surface, curve.FirstParameter(), curve.LastParameter(), v0 - reach, v1 + reach)
    return GeomConvert.SurfaceToBSplineSurface_s(bounded)


class TargetFaces:
    """Faces rays may meet: their support surfaces, boxes (for a quick miss) and classifiers."""

    def __init__(self, faces: dict[int, TopoDS_Face], reach: float) -> None:
        self.faces = faces
        self.surfaces = {i: _intersectable(f, reach) for i, f in faces.items()}
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
            meet = GeomAPI_IntCS(line, self.surfaces[i])
            if not meet.IsDone():
                continue
            for k in range(1, meet.NbPoints() + 1):
                p = xyz(meet.Point(k))
                distance = dot(sub(p, origin), direction)
                if 0.0 < distance <= reach:
                    found.append({"face": i, "distance": distance, "gap": self._gap(face, p)})
        found.sort(key=lambda h: (h["distance"], h["face"]))
        return found

    @staticmethod
    def _gap(face: TopoDS_Face, point: Vec) -> float:
        tolerance = BRep_Tool.Tolerance_s(face)
        if BRepClass_FaceClassifier(face, gp_Pnt(*point), tolerance).State() == TopAbs_IN:
            return 0.0
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*point)).Vertex()
        distance = BRepExtrema_DistShapeShape(vertex, face)
        if not distance.IsDone():
            raise KernelError("point-to-face distance failed")
        return distance.Value()


def probe(edges: list[tuple[TopoDS_Face, TopoDS_Shape, int]], targets: TargetFaces, samples: int, reach: float) -> list[dict[str, Any]]:
    """`edges`: (face, edge, own face index). One reply entry per edge."""
    out = []
    for face, edge, own in edges:
        entry: dict[str, list[Any]] = {"points": [], "normals": [], "outward": [], "hits": []}
        sampled = sample_edge(face, edge, samples)
        candidates = targets.near(sampled, reach, {own})
        for sample in sampled:
            entry["points"].append(list(sample.point))
            entry["normals"].append(list(sample.normal))
            entry["outward"].append(list(sample.outward))
            entry["hits"].append(targets.hits(sample.point, sample.outward, reach, candidates))
        out.append(entry)
    return out
