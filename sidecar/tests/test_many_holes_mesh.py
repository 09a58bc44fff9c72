"""A face with many holes (a perforated sheet) is meshed by BRepMesh's Delabella algorithm (constants.MANY_WIRES):
its mesh must be what Watson's would be for the rest of the pipeline: complete, facing out, nodes on the face."""

import math

from build123d import Face, Location, Plane, Wire, extrude
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_FACE
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS

from midsurf_sidecar.constants import MANY_WIRES
from midsurf_sidecar.describe import face_graph
from midsurf_sidecar.geom.topology import indexed_map

N, PITCH, D, T = 9, 6.0, 3.0, 1.5  # 81 holes: over MANY_WIRES


def perforated_sheet():
    side = (N + 1) * PITCH
    holes = [
        Wire.make_circle(D / 2, Plane.XY.move(Location((-side / 2 + PITCH * (i + 1), -side / 2 + PITCH * (j + 1), 0))))
        for i in range(N)
        for j in range(N)
    ]
    return extrude(Face(Wire.make_rect(side, side), holes), T).wrapped, side


def watson_area(solid, face_id: int) -> float:
    """The face meshed alone by BRepMesh's default algorithm, as every face was before: its triangles' area."""
    face = TopoDS.Face(indexed_map(solid, TopAbs_FACE).FindKey(face_id + 1))
    BRepTools.Clean_s(face)
    BRepMesh_IncrementalMesh(face, 0.0375, False, 0.5, False)
    tri = BRep_Tool.Triangulation_s(face, TopLoc_Location())
    area = 0.0
    for i in range(1, tri.NbTriangles() + 1):
        a, b, c = (tri.Node(k) for k in tri.Triangle(i).Get())
        area += 0.5 * a.XYZ().Subtracted(b.XYZ()).Crossed(a.XYZ().Subtracted(c.XYZ())).Modulus()
    return area


def test_a_sheet_with_many_holes_meshes_completely_and_outward():
    assert N * N + 1 > MANY_WIRES
    solid, side = perforated_sheet()
    described = face_graph.describe(solid, 0.0375)
    sheets = [f for f in described["faces"] if len(f["loops"]) == N * N + 1]
    assert len(sheets) == 2, "top and bottom carry every hole"
    for face in sheets:
        mesh = face["mesh"]
        v = mesh["vertices"]
        area = 0.0
        for a, b, c in mesh["triangles"]:
            u = [v[b][k] - v[a][k] for k in range(3)]
            w = [v[c][k] - v[a][k] for k in range(3)]
            n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
            # Every triangle faces the way the face does (out of the material).
            assert n[2] * face["normal"][2] > 0
            area += 0.5 * math.sqrt(sum(x * x for x in n))
        # Covers the same region as the default mesher's triangles: the face with polygonal holes.
        assert math.isclose(area, watson_area(solid, face["id"]), rel_tol=1e-9)
        assert math.isclose(area, face["area"], rel_tol=0.01), "the holes' polygons are close to circles"
        assert all(abs(p[2] - face["point"][2]) < 1e-9 for p in v), "nodes on the face's plane"
        assert not any(abs(p[0]) > side / 2 + 1e-9 or abs(p[1]) > side / 2 + 1e-9 for p in v)


def test_area_samples_of_a_face_with_many_holes_cover_it_and_are_on_it():
    """The samples interior_point falls back to when a face's UV centre is in a hole (it is here: N is odd)
    come from the same scalable mesher: they stand for the face's area, and each lies on the face."""
    from OCP.BRepClass import BRepClass_FaceClassifier
    from OCP.gp import gp_Pnt2d
    from OCP.TopAbs import TopAbs_IN

    from midsurf_sidecar.geom.face_meshing import has_many_wires
    from midsurf_sidecar.geom.face_point import area_samples
    from midsurf_sidecar.geom.topology import surface_props

    solid, side = perforated_sheet()
    faces = indexed_map(solid, TopAbs_FACE)
    sheet = next(TopoDS.Face(faces.FindKey(k)) for k in range(1, faces.Size() + 1) if has_many_wires(TopoDS.Face(faces.FindKey(k))))
    samples = area_samples(sheet, side * math.sqrt(2.0))
    area = surface_props(sheet).Mass()
    assert math.isclose(sum(a for a, _, _ in samples), area, rel_tol=0.01)
    assert all(BRepClass_FaceClassifier(sheet, gp_Pnt2d(u, v), 1e-7).State() == TopAbs_IN for _, u, v in samples)
