"""A point inside a face and its outward normal: the UV centre if inside the face, else a mesh point."""

from collections.abc import Iterator

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.gp import gp_Pnt2d
from OCP.TopAbs import TopAbs_IN
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face

from .errors import KernelError
from .face_normals import OutwardNormals
from .vectors import Vec, cross, norm, sub, xyz

# The fallback mesh only has to hold a few triangles well inside the face. Its deflection is a
# fraction of the face's bounding-box diagonal, so it scales with the face; chords of a coarse
# mesh cut across concave boundaries, hence each candidate is classified before it is used.
FALLBACK_DEFLECTION_RATIO = 0.01
FALLBACK_ANGLE = 0.5


def interior_point(normals: OutwardNormals, diagonal: float) -> tuple[Vec, Vec]:
    """(point, outward normal) inside the face; `diagonal` is the face's bounding-box diagonal."""
    face = normals.face
    for u, v in _candidates(face, diagonal):
        if _inside(face, u, v):
            sample = normals.at(u, v)
            if sample is not None:
                return sample
    raise KernelError("no point inside the face: neither the UV centre nor any mesh triangle centre")


def _candidates(face: TopoDS_Face, diagonal: float) -> Iterator[tuple[float, float]]:
    """The UV centre, then (meshing only if it gets that far) mesh triangle centres.

    A trimmed face (an L, a ring) need not contain its UV centre.
    """
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    yield 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    yield from _triangle_centroids(face, diagonal)


def _inside(face: TopoDS_Face, u: float, v: float) -> bool:
    classifier = BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), BRep_Tool.Tolerance_s(face))
    return classifier.State() == TopAbs_IN


def _triangle_centroids(face: TopoDS_Face, diagonal: float) -> list[tuple[float, float]]:
    """UV centroids of a coarse mesh's triangles, largest triangle first.

    The mesh is made on a copy so the face's own triangulation (what `describe` returns as `mesh`) is
    untouched and the result does not depend on earlier requests.
    """
    copy = TopoDS.Face(BRepBuilderAPI_Copy(face, False, False).Shape())
    BRepMesh_IncrementalMesh(copy, diagonal * FALLBACK_DEFLECTION_RATIO, False, FALLBACK_ANGLE)
    tri = BRep_Tool.Triangulation_s(copy, TopLoc_Location())
    if tri is None or not tri.HasUVNodes():
        return []
    candidates = []
    for i in range(1, tri.NbTriangles() + 1):
        a, b, c = tri.Triangle(i).Get()
        pa, pb, pc = xyz(tri.Node(a)), xyz(tri.Node(b)), xyz(tri.Node(c))
        area = norm(cross(sub(pb, pa), sub(pc, pa)))
        uvs = [tri.UVNode(k) for k in (a, b, c)]
        candidates.append((-area, i, sum(p.X() for p in uvs) / 3.0, sum(p.Y() for p in uvs) / 3.0))
    candidates.sort()
    return [(u, v) for _, _, u, v in candidates]
