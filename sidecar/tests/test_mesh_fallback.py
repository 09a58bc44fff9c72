"""mesh_shape's fallbacks: a face BRepMesh fails on is meshed again (finer angles, then a healed copy)."""

from pathlib import Path

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepGProp import BRepGProp
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Shape

from midsurf_sidecar.describe.face_mesh import face_mesh, mesh_shape

TINY_EDGES = Path(__file__).parent / "data" / "face_tiny_edges.brep"
TOLERANCE = 0.0375


def _face():
    shape = TopoDS_Shape()
    assert BRepTools.Read_s(shape, str(TINY_EDGES), BRep_Builder())
    return TopoDS.Face(TopExp_Explorer(shape, TopAbs_FACE).Current())


def _area(face) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face, props)
    return props.Mass()


def test_the_face_still_defeats_brepmesh_on_its_own():
    # The class the fallback is for: if BRepMesh learns to mesh this face, the test data no longer shows it.
    face = _face()
    for angle in (0.5, 0.1, 0.05):
        BRepTools.Clean_s(face)
        BRepMesh_IncrementalMesh(face, TOLERANCE, False, angle, False)
        assert BRep_Tool.Triangulation_s(face, TopLoc_Location()) is None


def test_a_face_with_micrometre_edges_gets_the_mesh_of_its_healed_copy():
    face = _face()
    mesh_shape(face, TOLERANCE)
    mesh = face_mesh(face, False)
    assert len(mesh["triangles"]) > 100
    area = 0.0
    for a, b, c in mesh["triangles"]:
        p, q, r = (mesh["vertices"][i] for i in (a, b, c))
        u = [q[k] - p[k] for k in range(3)]
        v = [r[k] - p[k] for k in range(3)]
        cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        area += 0.5 * sum(x * x for x in cross) ** 0.5
    # The same face: the mesh covers its area (within the chordal error of its arcs).
    assert abs(area - _area(face)) < 0.005 * _area(face)
    # Normals come from the face's own surface at the copy's UV nodes: a plane's, all along its normal.
    normals = {tuple(round(x, 6) for x in n) for n in mesh["normals"]}
    assert len(normals) == 1
