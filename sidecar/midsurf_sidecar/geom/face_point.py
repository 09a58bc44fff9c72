"""A point inside a face and its outward normal: the UV centre if inside the face, else a mesh point, else a
point just inside the middle of one of its edges (a sliver or a thin ring, where the other two miss)."""

import math
from collections.abc import Iterator

from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepTools import BRepTools
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec, gp_Vec2d
from OCP.TopAbs import TopAbs_IN
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face

from ..constants import (
    BESIDE_EDGE_STEPS, FALLBACK_ANGLE, FALLBACK_DEFLECTION_RATIO, MAX_AREA_SAMPLES, SINGULAR_METRIC,
)
from ..protocol.errors import KernelError
from .face_meshing import mesh_face
from .face_normals import OutwardNormals
from .topology import curve_edges
from .vectors import Vec, add_scaled, cross, dot, norm, scale, sub, xyz


def interior_point(normals: OutwardNormals, diagonal: float) -> tuple[Vec, Vec]:
    """(point, outward normal) inside the face; `diagonal` is the face's bounding-box diagonal."""
    face = normals.face
    for u, v in _candidates(face, diagonal):
        if _inside(face, u, v):
            sample = normals.at(u, v)
            if sample is not None:
                return sample
    raise KernelError(
        "no point inside the face: not the UV centre, nor a mesh triangle centre, nor a point beside an edge"
    )


def edge_point(normals: OutwardNormals) -> tuple[Vec, Vec]:
    """(point, outward normal) at the middle of the longest of the face's edges where the normal is defined (on
    a sliver, the middle of its length): for a sliver thinner than every step `interior_point` tries beside its
    edges, whose inside no classifier finds."""
    face = normals.face
    for edge in sorted(curve_edges(face), key=lambda e: -GCPnts_AbscissaPoint.Length_s(BRepAdaptor_Curve(e))):
        curve = BRepAdaptor_Curve2d(edge, face)
        uv = curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter()))
        sample = normals.at(uv.X(), uv.Y())
        if sample is not None:
            return sample
    raise KernelError("no point on the face: no edge with a defined normal at its middle")


def _candidates(face: TopoDS_Face, diagonal: float) -> Iterator[tuple[float, float]]:
    """The UV centre, then (meshing only if it gets that far) mesh triangle centres, then points beside
    the middle of each edge.

    A trimmed face (an L, a ring) need not contain its UV centre.
    """
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    yield 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    yield from _triangle_centroids(face, diagonal)
    yield from _beside_edges(face, diagonal)


def _inside(face: TopoDS_Face, u: float, v: float) -> bool:
    classifier = BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), BRep_Tool.Tolerance_s(face))
    return classifier.State() == TopAbs_IN


def _beside_edges(face: TopoDS_Face, diagonal: float) -> Iterator[tuple[float, float]]:
    """UV points on both sides of each edge's middle, ever closer to it (3D distances, so a surface's
    uneven parametrisation does not matter); the classifier keeps the inside ones."""
    surface = BRepAdaptor_Surface(face, False)
    for edge in curve_edges(face):
        curve = BRepAdaptor_Curve2d(edge, face)
        uv, tangent = gp_Pnt2d(), gp_Vec2d()
        curve.D1(0.5 * (curve.FirstParameter() + curve.LastParameter()), uv, tangent)
        side = _uv_across(surface, uv.X(), uv.Y(), tangent.X(), tangent.Y())
        if side is None:
            continue
        for step in BESIDE_EDGE_STEPS:
            for sign in (1.0, -1.0):
                offset = sign * step * diagonal
                yield uv.X() + offset * side[0], uv.Y() + offset * side[1]


def _uv_across(
    surface: BRepAdaptor_Surface, u: float, v: float, du: float, dv: float
) -> tuple[float, float] | None:
    """The UV step that moves 1 mm on the surface at right angles to the UV direction (du, dv)."""
    point, su, sv = gp_Pnt(), gp_Vec(), gp_Vec()
    surface.D1(u, v, point, su, sv)
    along = xyz(su) if dv == 0.0 else add_scaled(scale(xyz(su), du), xyz(sv), dv)
    across = cross(cross(xyz(su), xyz(sv)), along)
    # Least squares: a su + b sv = across.
    uu, uv_, vv = dot(xyz(su), xyz(su)), dot(xyz(su), xyz(sv)), dot(xyz(sv), xyz(sv))
    det = uu * vv - uv_ * uv_
    if det <= SINGULAR_METRIC:
        return None
    wu, wv = dot(xyz(su), across), dot(xyz(sv), across)
    a, b = (vv * wu - uv_ * wv) / det, (uu * wv - uv_ * wu) / det
    length = norm(add_scaled(scale(xyz(su), a), xyz(sv), b))
    return (a / length, b / length) if length > 0.0 else None


def _triangle_centroids(face: TopoDS_Face, diagonal: float) -> list[tuple[float, float]]:
    """UV centroids of a coarse mesh's triangles, largest triangle first."""
    candidates = sorted((-area, i, u, v) for i, (area, u, v) in enumerate(area_samples(face, diagonal)))
    return [(u, v) for _, _, u, v in candidates]


def area_samples(face: TopoDS_Face, diagonal: float, step: float | None = None) -> list[tuple[float, float, float]]:
    """(area, u, v) of each triangle of a coarse mesh of the face (`diagonal`: its bounding-box diagonal): the
    UV centroid and the share of the face it stands for; [] when the face does not mesh. With `step`, each
    triangle is split in four until no side is longer than `step` (a plane's mesh only joins its boundary's
    vertices: long slivers), so that every sample stands for a small region.

    The mesh is made on a copy so the face's own triangulation (what `describe` returns as `mesh`) is
    untouched and the result does not depend on earlier requests.
    """
    copy = TopoDS.Face(BRepBuilderAPI_Copy(face, False, False).Shape())
    mesh_face(copy, diagonal * FALLBACK_DEFLECTION_RATIO, FALLBACK_ANGLE)
    tri = BRep_Tool.Triangulation_s(copy, TopLoc_Location())
    if tri is None or not tri.HasUVNodes():
        return []
    triangles = [
        [(xyz(tri.Node(k)), (tri.UVNode(k).X(), tri.UVNode(k).Y())) for k in tri.Triangle(i).Get()]
        for i in range(1, tri.NbTriangles() + 1)
    ]
    if step is not None:
        # Coarser steps until the samples number MAX_AREA_SAMPLES at most: a bound on the work, evenly spread.
        while sum(4 ** _splits(t, step) for t in triangles) > MAX_AREA_SAMPLES:
            step *= 2.0
    samples = []
    for corners in triangles:
        _subdivide(corners, step, samples)
    return samples


def _splits(corners, step: float) -> int:
    """How many times _subdivide halves the triangle `corners` for sides of `step` at most."""
    longest = max(norm(sub(corners[k][0], corners[k - 1][0])) for k in range(3))
    return max(0, math.ceil(math.log2(longest / step))) if longest > step else 0


def _subdivide(corners, step: float | None, out: list[tuple[float, float, float]]) -> None:
    """Append (area, u, v) of the triangle `corners` ((point, uv) each), split in four (by its sides' middles,
    in 3D and in UV alike: exact on a plane, close on a finely meshed curved face) while a side exceeds `step`."""
    (pa, ta), (pb, tb), (pc, tc) = corners
    longest = max(norm(sub(pb, pa)), norm(sub(pc, pb)), norm(sub(pa, pc)))
    if step is None or longest <= step:
        area = 0.5 * norm(cross(sub(pb, pa), sub(pc, pa)))
        out.append((area, (ta[0] + tb[0] + tc[0]) / 3.0, (ta[1] + tb[1] + tc[1]) / 3.0))
        return

    def middle(p, q):
        return scale(add_scaled(p[0], q[0], 1.0), 0.5), (0.5 * (p[1][0] + q[1][0]), 0.5 * (p[1][1] + q[1][1]))

    a, b, c = corners
    ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
    for triangle in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)):
        _subdivide(triangle, step, out)
