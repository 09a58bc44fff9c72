"""describe: the face graph — surfaces, outward normals, loops, edge convexity, meshes."""

import json
import math
from collections import Counter

import pytest
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepGProp import BRepGProp
from OCP.BRepOffset import BRepOffset_Analyse
from OCP.ChFiDS import ChFiDS_Concave, ChFiDS_Convex, ChFiDS_Tangential
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_IN, TopAbs_OUT
from OCP.TopoDS import TopoDS

from midsurf_sidecar.geom.topology import indexed_map
from shapes import (
    BEND_CENTRE,
    BEND_INNER,
    BEND_OUTER,
    L_PROFILE,
    bent_sheet,
    box,
    box_with_void,
    cone,
    l_extrusion,
    plate_with_hole,
    shaft,
    sphere,
    torus,
)

RIGHT = math.pi / 2


def describe(client, shape, tmp_path, **args):
    return client.ok("describe", handle=client.load(shape, tmp_path), **args)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def faces_of_kind(graph, kind):
    return [f for f in graph["faces"] if f["surface"]["kind"] == kind]


def edges_between(graph, face_a, face_b):
    return [e for e in graph["edges"] if e["faces"] == sorted([face_a, face_b])]


def test_box_graph(client, tmp_path):
    graph = describe(client, box(10, 20, 30), tmp_path)
    assert graph["volume"] == pytest.approx(6000.0)
    assert graph["bbox"]["min"] == pytest.approx([0, 0, 0], abs=1e-9)
    assert graph["bbox"]["max"] == pytest.approx([10, 20, 30], abs=1e-9)
    assert len(graph["vertices"]) == 8
    assert [f["id"] for f in graph["faces"]] == list(range(6))
    assert [e["id"] for e in graph["edges"]] == list(range(12))

    centre = [5, 10, 15]
    for face in graph["faces"]:
        assert list(face["surface"])[0] == "kind"
        assert face["surface"]["kind"] == "plane"
        assert face["surface"]["normal"] == pytest.approx(face["normal"])
        assert dot(face["normal"], sub(face["centroid"], centre)) > 0, "normals point out of the box"
        assert len(face["loops"]) == 1 and len(face["loops"][0]) == 4
        assert "mesh" not in face
        for edge_id in face["loops"][0]:
            assert face["id"] in graph["edges"][edge_id]["faces"]

    for edge in graph["edges"]:
        assert edge["convexity"] == "convex"
        assert edge["angle"] == pytest.approx(RIGHT)
        assert edge["curve"] == "line"
        assert len(edge["faces"]) == 2 and edge["faces"] == sorted(edge["faces"])
        a, b = (graph["vertices"][v] for v in edge["vertices"])
        assert edge["length"] == pytest.approx(math.dist(a, b))
        assert edge["midpoint"] == pytest.approx([(x + y) / 2 for x, y in zip(a, b)])


def test_face_ids_follow_mapshapes_order(client, tmp_path):
    handle = client.load(plate_with_hole(), tmp_path)
    graph = client.ok("describe", handle=handle)
    face_map = indexed_map(client.session.store.get(handle), TopAbs_FACE)
    for face in graph["faces"]:
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(face_map.FindKey(face["id"] + 1), props)
        assert face["area"] == pytest.approx(props.Mass())


def test_l_extrusion_has_exactly_one_concave_edge(client, tmp_path):
    graph = describe(client, l_extrusion(), tmp_path)
    concave = [e for e in graph["edges"] if e["convexity"] == "concave"]
    assert len(concave) == 1
    assert concave[0]["angle"] == pytest.approx(-RIGHT)
    assert concave[0]["midpoint"] == pytest.approx([5, 5, 5])
    assert Counter(e["convexity"] for e in graph["edges"]) == {"convex": 17, "concave": 1}


def test_point_lies_inside_a_face_whose_uv_centre_does_not(client, tmp_path):
    graph = describe(client, l_extrusion(), tmp_path)
    (top,) = [f for f in graph["faces"] if f["normal"] == pytest.approx([0, 0, 1])]
    x, y, z = top["point"]
    # The L's bounding-box centre (10, 10) is outside the L.
    assert z == pytest.approx(10.0)
    assert 0 < x < 20 and 0 < y < 20 and (x < 5 or y < 5), top["point"]
    assert len(top["loops"][0]) == len(L_PROFILE)


def test_plate_with_hole(client, tmp_path):
    graph = describe(client, plate_with_hole(radius=5.0), tmp_path)
    (hole,) = faces_of_kind(graph, "cylinder")
    surface = hole["surface"]
    assert surface["radius"] == pytest.approx(5.0)
    assert surface["convex"] is False
    # A hole's outward normal (out of the material) points at its axis.
    towards_axis = sub([20, 20, hole["point"][2]], hole["point"])
    assert dot(hole["normal"], towards_axis) > 0

    top = next(f for f in graph["faces"] if f["normal"] == pytest.approx([0, 0, 1]))
    bottom = next(f for f in graph["faces"] if f["normal"] == pytest.approx([0, 0, -1]))
    # Plate rims: 90 degrees of material at the edge of the hole, a convex edge.
    for cap in (top, bottom):
        (rim,) = edges_between(graph, hole["id"], cap["id"])
        assert rim["convexity"] == "convex"
        assert rim["angle"] == pytest.approx(RIGHT)
        assert rim["curve"] == "circle"
        assert rim["length"] == pytest.approx(2 * math.pi * 5.0)
        # The top face has two loops, the outer square first.
        assert len(cap["loops"]) == 2
        assert len(cap["loops"][0]) == 4
        assert rim["id"] in cap["loops"][1]

    (seam,) = [e for e in graph["edges"] if e["convexity"] == "seam"]
    assert seam["faces"] == [hole["id"]]
    assert seam["angle"] == 0
    assert hole["loops"][0].count(seam["id"]) == 2


def test_shaft_cylinder_is_convex(client, tmp_path):
    graph = describe(client, shaft(radius=5.0, length=20.0), tmp_path)
    (side,) = faces_of_kind(graph, "cylinder")
    assert side["surface"]["convex"] is True
    assert side["surface"]["radius"] == pytest.approx(5.0)
    assert [abs(c) for c in side["surface"]["axis"]] == pytest.approx([0, 0, 1])
    assert Counter(e["convexity"] for e in graph["edges"]) == {"convex": 2, "seam": 1}


def test_bent_sheet(client, tmp_path):
    graph = describe(client, bent_sheet(), tmp_path)
    bends = {round(f["surface"]["radius"], 6): f for f in faces_of_kind(graph, "cylinder")}
    assert set(bends) == {BEND_INNER, BEND_OUTER}
    assert bends[BEND_OUTER]["surface"]["convex"] is True
    assert bends[BEND_INNER]["surface"]["convex"] is False
    assert bends[BEND_OUTER]["surface"]["origin"][:2] == pytest.approx(list(BEND_CENTRE))
    for bend in bends.values():
        for edge in graph["edges"]:
            if bend["id"] in edge["faces"] and edge["curve"] == "line":
                # Where the bend runs into a flange, the faces are tangent.
                assert edge["convexity"] == "smooth"
                assert abs(edge["angle"]) < math.radians(1)
    assert Counter(e["convexity"] for e in graph["edges"]) == {"smooth": 4, "convex": 20}


def test_sphere_has_seam_and_degenerate_edges(client, tmp_path):
    graph = describe(client, sphere(5.0), tmp_path)
    (face,) = graph["faces"]
    assert face["surface"] == {
        "kind": "sphere", "center": pytest.approx([0, 0, 0]), "radius": pytest.approx(5.0), "convex": True
    }
    assert dot(face["normal"], face["point"]) == pytest.approx(5.0)
    convexity = Counter(e["convexity"] for e in graph["edges"])
    assert convexity == {"seam": 1, "degenerate": 2}
    for edge in graph["edges"]:
        if edge["convexity"] == "degenerate":
            assert edge["length"] == 0 and edge["angle"] == 0
            assert abs(edge["midpoint"][2]) == pytest.approx(5.0)


def test_torus_is_convex_even_where_the_normal_faces_the_axis(client, tmp_path):
    graph = describe(client, torus(10.0, 2.0), tmp_path)
    (face,) = graph["faces"]
    surface = face["surface"]
    assert surface["major_radius"] == pytest.approx(10.0)
    assert surface["minor_radius"] == pytest.approx(2.0)
    assert surface["convex"] is True


def test_cone(client, tmp_path):
    graph = describe(client, cone(), tmp_path)
    (side,) = faces_of_kind(graph, "cone")
    surface = side["surface"]
    assert surface["convex"] is True
    assert abs(surface["half_angle"]) == pytest.approx(math.atan2(3.0, 10.0))
    assert surface["apex"] == pytest.approx([0, 0, 50.0 / 3.0])


def test_void_sphere_is_concave(client, tmp_path):
    graph = describe(client, box_with_void(), tmp_path)
    (void,) = faces_of_kind(graph, "sphere")
    assert void["surface"]["convex"] is False
    assert void["reversed"] is True
    assert dot(void["normal"], sub(void["point"], [10, 10, 10])) < 0
    assert graph["volume"] == pytest.approx(8000 - 4 / 3 * math.pi * 64, rel=1e-6)


def test_mesh_is_ccw_from_outside_with_outward_normals(client, tmp_path):
    graph = describe(client, plate_with_hole(), tmp_path, mesh=True, mesh_tolerance=0.05)
    for face in graph["faces"]:
        mesh = face["mesh"]
        vertices, normals = mesh["vertices"], mesh["normals"]
        assert len(vertices) == len(normals) > 0 and mesh["triangles"]
        area = 0.0
        for a, b, c in mesh["triangles"]:
            u, v = sub(vertices[b], vertices[a]), sub(vertices[c], vertices[a])
            cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            area += math.sqrt(dot(cross, cross)) / 2
            assert dot(cross, normals[a]) > 0
        for n in normals:
            assert math.sqrt(dot(n, n)) == pytest.approx(1.0)
        if face["surface"]["kind"] == "plane":
            assert all(n == pytest.approx(face["normal"]) for n in normals)
            # A polygonal mesh of a face with a hole slightly overestimates it.
            assert area == pytest.approx(face["area"], rel=1e-2)
        else:
            towards_axis = [[20 - p[0], 20 - p[1], 0] for p in vertices]
            assert all(dot(n, t) > 0 for n, t in zip(normals, towards_axis))


def test_mesh_depends_only_on_the_request(client, tmp_path):
    handle = client.load(plate_with_hole(), tmp_path)
    fine = client.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.01)
    coarse = client.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.5)
    again = client.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.01)
    assert json.dumps(again) == json.dumps(fine)
    assert len(coarse["faces"][0]["mesh"]["vertices"]) <= len(fine["faces"][0]["mesh"]["vertices"])
    hole = next(f for f in fine["faces"] if f["surface"]["kind"] == "cylinder")
    coarse_hole = coarse["faces"][hole["id"]]
    assert len(coarse_hole["mesh"]["triangles"]) < len(hole["mesh"]["triangles"])


def test_describe_argument_errors(client, tmp_path):
    handle = client.load(box(), tmp_path)
    assert client.err("describe")["code"] == "bad_args"
    assert client.err("describe", handle=handle + 1000)["code"] == "bad_args"
    assert client.err("describe", handle=handle, mesh=True)["code"] == "bad_args"
    assert client.err("describe", handle=handle, mesh=True, mesh_tolerance=-1)["code"] == "bad_args"
    assert client.err("describe", handle=handle, mesh="yes", mesh_tolerance=0.1)["code"] == "bad_args"
    too_fine = client.err("describe", handle=handle, mesh=True, mesh_tolerance=1e-9)
    assert too_fine["code"] == "bad_args" and "too fine" in too_fine["message"]


def test_e_plate_graph_is_consistent(e_plate):
    _, _, graph = e_plate
    assert len(graph["faces"]) == 56
    assert graph["volume"] == pytest.approx(9859.45, rel=1e-3)
    size = [b - a for a, b in zip(graph["bbox"]["min"], graph["bbox"]["max"])]
    assert size == pytest.approx([64, 64, 27.4], abs=0.01)
    in_loops = Counter(e for f in graph["faces"] for loop in f["loops"] for e in loop)
    for edge in graph["edges"]:
        expected_uses = 1 if edge["convexity"] == "degenerate" else 2
        assert in_loops[edge["id"]] == expected_uses, edge
        assert all(edge["id"] in sum(graph["faces"][f]["loops"], []) for f in edge["faces"])


def test_e_plate_points_lie_on_faces_with_outward_normals(e_plate):
    client, handle, graph = e_plate
    solid = client.session.store.get(handle)
    step = 1e-3
    for face in graph["faces"]:
        p, n = face["point"], face["normal"]
        outside = BRepClass3d_SolidClassifier(solid, gp_Pnt(*[p[i] + step * n[i] for i in range(3)]), 1e-7)
        inside = BRepClass3d_SolidClassifier(solid, gp_Pnt(*[p[i] - step * n[i] for i in range(3)]), 1e-7)
        assert (outside.State(), inside.State()) == (TopAbs_OUT, TopAbs_IN), face["id"]


def test_e_plate_convexity_agrees_with_brepoffset_analyse(e_plate):
    client, handle, graph = e_plate
    solid = client.session.store.get(handle)
    analyse = BRepOffset_Analyse(solid, math.radians(1.0))
    edge_map = indexed_map(solid, TopAbs_EDGE)
    names = {ChFiDS_Convex: "convex", ChFiDS_Concave: "concave", ChFiDS_Tangential: "smooth"}
    compared = 0
    for edge in graph["edges"]:
        if edge["convexity"] in names.values():
            intervals = analyse.Type(TopoDS.Edge(edge_map.FindKey(edge["id"] + 1)))
            assert names[intervals.First().Type()] == edge["convexity"], edge
            compared += 1
    assert compared > 100


@pytest.mark.parametrize("make", [plate_with_hole, sphere, bent_sheet])
def test_mesh_gives_the_triangles_describe_gives_and_nothing_else(client, tmp_path, make):
    handle = client.load(make(), tmp_path)
    described = client.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.05)
    meshed = client.ok("mesh", handle=handle, mesh_tolerance=0.05)
    assert list(meshed) == ["faces"]
    assert meshed["faces"] == [f["mesh"] for f in described["faces"]]
    assert all(m["triangles"] for m in meshed["faces"])
