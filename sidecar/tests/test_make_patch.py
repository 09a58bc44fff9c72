"""make_patch: faces offset along their outward normals or projected onto a plane, as a compound."""

import math
from pathlib import Path

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon, BRepBuilderAPI_NurbsConvert
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cylinder, GeomAbs_OffsetSurface, GeomAbs_Plane
from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_FACE, TopAbs_VERTEX, TopAbs_WIRE
from OCP.TopoDS import TopoDS

from midsurf_sidecar.geom.topology import indexed_map
from shapes import (
    BEND_CENTRE,
    BEND_INNER,
    BEND_OUTER,
    bent_sheet,
    box,
    cone,
    plate_with_hole,
    shaft,
    sphere,
    torus,
)

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
# drafted_rib.step: 100 x 60 x 3 plate, rib 20 high centred on x = 50, faces 7 and 8 its drafted sides.
RIB_SIDES = [7, 8]
RIB_PLANE = {"origin": [50.0, 0.0, 0.0], "normal": [1.0, 0.0, 0.0]}


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def load_fixture(client, name):
    return client.ok("load_step", path=str(FIXTURES / name))["solids"][0]["handle"]


def graph(client, handle):
    return client.ok("describe", handle=handle)


def face_with(graph_json, kind, predicate=lambda f: True):
    matches = [f for f in graph_json["faces"] if f["surface"]["kind"] == kind and predicate(f)]
    assert len(matches) == 1, [f["id"] for f in matches]
    return matches[0]


def patch_faces(client, handle):
    shape = client.session.store.get(handle)
    assert shape.ShapeType() == TopAbs_COMPOUND
    faces = indexed_map(shape, TopAbs_FACE)
    return [TopoDS.Face(faces.FindKey(i + 1)) for i in range(faces.Size())]


def vertices(shape):
    vertex_map = indexed_map(shape, TopAbs_VERTEX)
    points = [BRep_Tool.Pnt_s(TopoDS.Vertex(vertex_map.FindKey(i + 1))) for i in range(vertex_map.Size())]
    return [(p.X(), p.Y(), p.Z()) for p in points]


def test_plate_faces_move_into_the_material(client, tmp_path):
    handle = client.load(box(40, 40, 5), tmp_path)
    g = graph(client, handle)
    top = face_with(g, "plane", lambda f: f["normal"][2] > 0.99)["id"]
    bottom = face_with(g, "plane", lambda f: f["normal"][2] < -0.99)["id"]
    ok = client.ok("make_patch", handle=handle, faces=[top, bottom], offset=-1.0)
    assert [f["source"] for f in ok["faces"]] == [top, bottom]
    upper, lower = ok["faces"]
    assert upper["area"] == pytest.approx(1600.0)
    assert upper["centroid"] == pytest.approx([20, 20, 4])
    assert upper["normal"] == pytest.approx([0, 0, 1], abs=1e-12)
    assert lower["centroid"] == pytest.approx([20, 20, 1])
    assert lower["normal"] == pytest.approx([0, 0, -1], abs=1e-12)
    # The compound holds the new faces in request order.
    new_top, new_bottom = patch_faces(client, ok["handle"])
    assert {round(z, 9) for _, _, z in vertices(new_top)} == {4.0}
    assert {round(z, 9) for _, _, z in vertices(new_bottom)} == {1.0}
    assert BRepCheck_Analyzer(client.session.store.get(ok["handle"])).IsValid()


def test_a_patch_on_its_own_skin_is_a_copy_and_reverse_turns_it_over(client, tmp_path):
    handle = client.load(box(40, 40, 5), tmp_path)
    top = face_with(graph(client, handle), "plane", lambda f: f["normal"][2] > 0.99)["id"]
    same = client.ok("make_patch", handle=handle, faces=[top], offset=0.0)["faces"][0]
    assert same["centroid"] == pytest.approx([20, 20, 5])
    assert same["normal"] == pytest.approx([0, 0, 1], abs=1e-12)
    # Moved onto the bottom skin and turned over: the normal points out of the bottom side, as it does when
    # the bottom is a wall's top side.
    ok = client.ok("make_patch", handle=handle, faces=[top], offset=-5.0, reverse=True)
    assert ok["faces"][0]["centroid"] == pytest.approx([20, 20, 0])
    assert ok["faces"][0]["normal"] == pytest.approx([0, 0, -1], abs=1e-12)
    (face,) = patch_faces(client, ok["handle"])
    assert {round(z, 9) for _, _, z in vertices(face)} == {0.0}
    err = client.err("make_patch", handle=handle, faces=[top], offset=0.0, reverse="yes")
    assert "reverse" in err["message"]


def test_bend_cylinders_meet_at_the_mid_radius(client, tmp_path):
    handle = client.load(bent_sheet(), tmp_path)
    g = graph(client, handle)
    outer = face_with(g, "cylinder", lambda f: f["surface"]["convex"])
    inner = face_with(g, "cylinder", lambda f: not f["surface"]["convex"])
    assert (outer["surface"]["radius"], inner["surface"]["radius"]) == pytest.approx((BEND_OUTER, BEND_INNER))
    ok = client.ok("make_patch", handle=handle, faces=[outer["id"], inner["id"]], offset=-1.0)
    for new_face, described, source in zip(patch_faces(client, ok["handle"]), ok["faces"], (outer, inner)):
        surface = BRepAdaptor_Surface(new_face)
        assert surface.GetType() == GeomAbs_Cylinder
        assert surface.Cylinder().Radius() == pytest.approx(4.0)
        assert surface.Cylinder().Location().X() == pytest.approx(BEND_CENTRE[0])
        assert surface.Cylinder().Location().Y() == pytest.approx(BEND_CENTRE[1])
        # A quarter turn of radius 4, 10 long; the outward normal keeps its side.
        assert described["area"] == pytest.approx(math.pi / 2 * 4.0 * 10.0)
        assert dot(described["normal"], source["normal"]) > 0.99


def assert_on_radius(surface, face, radius):
    """Points across the middle of `face` lie at `radius` from the z axis (within 1e-6 mm)."""
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    for u in (0.1, 0.5, 0.9):
        p = surface.Value(u0 + u * (u1 - u0), 0.5 * (v0 + v1))
        assert math.hypot(p.X(), p.Y()) == pytest.approx(radius, abs=1e-6)


def test_bspline_face_offsets(client, tmp_path):
    converter = BRepBuilderAPI_NurbsConvert(shaft(5.0, 20.0), True)
    handle = client.load(converter.Shape(), tmp_path)
    faces = indexed_map(client.session.store.get(handle), TopAbs_FACE)
    kinds = [BRepAdaptor_Surface(TopoDS.Face(faces.FindKey(i + 1))).GetType() for i in range(faces.Size())]
    assert set(kinds) == {GeomAbs_BSplineSurface}
    lateral = max(graph(client, handle)["faces"], key=lambda f: f["area"])
    ok = client.ok("make_patch", handle=handle, faces=[lateral["id"]], offset=-1.0)
    (new_face,) = patch_faces(client, ok["handle"])
    surface = BRepAdaptor_Surface(new_face)
    assert surface.GetType() == GeomAbs_OffsetSurface
    assert_on_radius(surface, new_face, 4.0)
    # BRepGProp integrates the rational surface 0.3 % high, the same way on both: radius 5 -> 4.
    assert ok["faces"][0]["area"] == pytest.approx(lateral["area"] * 4.0 / 5.0, rel=1e-6)
    assert ok["faces"][0]["area"] == pytest.approx(2 * math.pi * 4.0 * 20.0, rel=1e-2)
    assert ok["faces"][0]["centroid"] == pytest.approx([0, 0, 10], abs=1e-2)


def test_thin_ring_gets_an_interior_normal(client, tmp_path):
    # A tube 0.5 mm thick and 51 m in radius: its UV centre and coarse-mesh triangles all miss the top face.
    section = BRepBuilderAPI_MakePolygon()
    for x, z in ((50999.5, 0.0), (51000.0, 0.0), (51000.0, 10.0), (50999.5, 10.0)):
        section.Add(gp_Pnt(x, 0.0, z))
    section.Close()
    face = BRepBuilderAPI_MakeFace(section.Wire(), True).Face()
    tube = BRepPrimAPI_MakeRevol(face, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))).Shape()
    handle = client.load(tube, tmp_path)
    top = face_with(graph(client, handle), "plane", lambda f: f["normal"][2] > 0.99)
    ok = client.ok("make_patch", handle=handle, faces=[top["id"]], offset=-1.0)
    assert ok["faces"][0]["normal"] == pytest.approx([0, 0, 1], abs=1e-12)
    assert ok["faces"][0]["centroid"][2] == pytest.approx(9.0)


def test_cone_offset_shrinks_the_radius_by_the_cosine(client, tmp_path):
    handle = client.load(cone(), tmp_path)  # radii 5 -> 2 over 10
    lateral = face_with(graph(client, handle), "cone")
    ok = client.ok("make_patch", handle=handle, faces=[lateral["id"]], offset=-1.0)
    half_angle = math.atan2(3.0, 10.0)
    (new_face,) = patch_faces(client, ok["handle"])
    rims = sorted({(round(math.hypot(x, y), 9), round(z, 9)) for x, y, z in vertices(new_face)})
    # The normal leans up by the half angle: each rim moves in by its cosine and up by its sine. The bottom rim
    # would then hang below the base, outside the solid: it is cut at the base, where the offset cone's radius
    # is 5 - 1 / cos(half angle).
    shift_in, shift_up = math.cos(half_angle), math.sin(half_angle)
    assert len(rims) == 2
    assert rims[0] == pytest.approx((2.0 - shift_in, 10.0 - shift_up))
    assert rims[1] == pytest.approx((5.0 - 1.0 / math.cos(half_angle), 0.0))
    assert dot(ok["faces"][0]["normal"], lateral["normal"]) > 0.99


@pytest.mark.parametrize(
    ("shape", "kind", "offset"),
    [
        (shaft(5.0), "cylinder", -5.0),  # convex: d < 0 shrinks the radius to 0
        (plate_with_hole(5.0), "cylinder", 5.0),  # concave (a hole): d > 0 shrinks it
        (sphere(5.0), "sphere", -5.0),
        (torus(10.0, 2.0), "torus", -2.0),
        (cone(), "cone", -2.5),  # smallest radius 2, shrinks by 2.5 cos(16.7 deg) = 2.39
    ],
)
def test_collapsing_offsets_are_refused(client, tmp_path, shape, kind, offset):
    handle = client.load(shape, tmp_path)
    face = face_with(graph(client, handle), kind)["id"]
    err = client.err("make_patch", handle=handle, faces=[face], offset=offset)
    assert err["code"] == "patch_failed"
    assert err["message"].startswith(f"face {face}: ")
    assert "collapse" in err["message"]
    # Just short of the axis is fine.
    shorter = offset * 0.9 if kind != "cone" else -2.0
    assert client.ok("make_patch", handle=handle, faces=[face], offset=shorter)["faces"][0]["area"] > 0


def test_draft_sides_project_onto_the_bisector_plane(client):
    handle = load_fixture(client, "drafted_rib.step")
    g = graph(client, handle)
    sources = [g["faces"][i] for i in RIB_SIDES]
    ok = client.ok("make_patch", handle=handle, faces=RIB_SIDES, plane=RIB_PLANE)
    assert [f["source"] for f in ok["faces"]] == RIB_SIDES
    patch = client.session.store.get(ok["handle"])
    assert BRepCheck_Analyzer(patch).IsValid()
    for new_face, described, source in zip(patch_faces(client, ok["handle"]), ok["faces"], sources):
        assert BRepCheck_Analyzer(new_face).IsValid()
        assert BRepAdaptor_Surface(new_face).GetType() == GeomAbs_Plane
        points = vertices(new_face)
        assert len(points) == 4
        assert all(x == pytest.approx(50.0, abs=1e-9) for x, _, _ in points)
        # The side spans y 0..60 and z 3..23: its shadow on x = 50 is a 60 x 20 rectangle.
        corners = sorted({(round(y, 9), round(z, 9)) for _, y, z in points})
        assert corners == [(0, 3), (0, 23), (60, 3), (60, 23)]
        assert described["area"] == pytest.approx(60.0 * 20.0)
        assert described["centroid"] == pytest.approx([50, 30, 13])
        # Plane normal or its opposite, whichever the source side faces.
        side = math.copysign(1.0, source["normal"][0])
        assert described["normal"] == pytest.approx([side, 0, 0], abs=1e-12)
    assert [f["normal"][0] for f in ok["faces"]] == pytest.approx([-1.0, 1.0])


def test_projection_keeps_holes_and_orientation(client, tmp_path):
    handle = client.load(plate_with_hole(5.0), tmp_path)
    g = graph(client, handle)
    top = face_with(g, "plane", lambda f: f["normal"][2] > 0.99)
    bottom = face_with(g, "plane", lambda f: f["normal"][2] < -0.99)
    tilt = [0.1, 0.2, 1.0]
    length = math.sqrt(dot(tilt, tilt))
    unit = [c / length for c in tilt]
    origin = [20.0, 20.0, 2.5]
    ok = client.ok("make_patch", handle=handle, faces=[top["id"], bottom["id"]],
                   plane={"origin": origin, "normal": tilt})
    area = 40 * 40 - math.pi * 25
    for new_face, described, sign in zip(patch_faces(client, ok["handle"]), ok["faces"], (1.0, -1.0)):
        assert BRepCheck_Analyzer(new_face).IsValid()
        assert indexed_map(new_face, TopAbs_WIRE).Size() == 2
        # A region of area A with normal z, projected along n: A |n_z| (the shadow of the hole too).
        assert described["area"] == pytest.approx(area * unit[2], rel=1e-6)
        assert described["normal"] == pytest.approx([sign * c for c in unit], abs=1e-9)
        for point in vertices(new_face):
            assert dot([p - o for p, o in zip(point, origin)], unit) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("nurbs", [False, True])
def test_projection_of_arcs_and_closed_splines_onto_a_tilted_plane(client, tmp_path, nurbs):
    # Tilted so that ProjLib flips the sense of the bend's clockwise arc (it then trims the ellipse on
    # the wrong, 3/4 arc); as NURBS, the hole is one closed, non-periodic B-spline edge.
    shape = plate_with_hole(5.0) if nurbs else bent_sheet()
    if nurbs:
        shape = BRepBuilderAPI_NurbsConvert(shape, True).Shape()
    handle = client.load(shape, tmp_path)
    caps = [f for f in graph(client, handle)["faces"] if abs(f["normal"][2]) > 0.99]
    assert len(caps) == 2
    tilt = [0.01, -0.02, 1.015]
    cosine = tilt[2] / math.sqrt(dot(tilt, tilt))
    ok = client.ok("make_patch", handle=handle, faces=[f["id"] for f in caps],
                   plane={"origin": [1.0, 2.0, 3.0], "normal": tilt})
    for new_face, described, source in zip(patch_faces(client, ok["handle"]), ok["faces"], caps):
        assert BRepCheck_Analyzer(new_face).IsValid()
        # BRepGProp integrates rational B-splines only to ~1e-4.
        assert described["area"] == pytest.approx(source["area"] * cosine, rel=1e-3 if nurbs else 1e-9)
        assert dot(described["normal"], source["normal"]) > 0.99


def test_edge_on_face_cannot_be_projected(client):
    handle = load_fixture(client, "drafted_rib.step")
    err = client.err("make_patch", handle=handle, faces=[7, 4], plane=RIB_PLANE)  # 4: the plate's underside
    assert err["code"] == "patch_failed"
    assert err["message"].startswith("face 4: ") and "edge-on" in err["message"]


def test_failed_patch_leaves_no_handle(client, tmp_path):
    handle = client.load(shaft(5.0), tmp_path)
    lateral = face_with(graph(client, handle), "cylinder")["id"]
    client.err("make_patch", handle=handle, faces=[lateral], offset=-10.0)
    ok = client.ok("make_patch", handle=handle, faces=[lateral], offset=-1.0)
    assert ok["handle"] == handle + 1


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ({"faces": [6], "offset": -1.0}, "face 6 out of range"),
        ({"faces": [-1], "offset": -1.0}, "face -1 out of range"),
        ({"faces": [0, 0], "offset": -1.0}, "face 0 is listed twice"),
        ({"faces": [], "offset": -1.0}, "at least one face"),
        ({"faces": "all", "offset": -1.0}, "must be a list"),
        ({"faces": [True], "offset": -1.0}, "integers"),
        ({"faces": [0]}, "exactly one of"),
        ({"faces": [0], "offset": -1.0, "plane": RIB_PLANE}, "exactly one of"),
        ({"faces": [0], "offset": "thin"}, "`offset`"),
        ({"faces": [0], "offset": float("nan")}, None),
        ({"faces": [0], "plane": {"origin": [0, 0, 0], "normal": [0, 0, 0]}}, "non-zero"),
        ({"faces": [0], "plane": {"origin": [0, 0], "normal": [0, 0, 1]}}, "`origin`"),
        ({"faces": [0], "plane": [0, 0, 1]}, "`plane`"),
    ],
)
def test_bad_arguments(client, tmp_path, args, needle):
    handle = client.load(box(), tmp_path)
    err = client.err("make_patch", handle=handle, **args)
    assert err["code"] == "bad_args", err
    if needle is not None:
        assert needle in err["message"]


@pytest.mark.parametrize("handle", [0, -1, 99, "1"])
def test_bad_handles(client, handle):
    assert client.err("make_patch", handle=handle, faces=[0], offset=-1.0)["code"] == "bad_args"


# A step in an extruded profile: the bottom (y = 0, x 0..100) faces a 2 mm top over x 60..100 and a 5 mm top
# over x 0..60.
STEP_PROFILE = [(0.0, 0.0), (100.0, 0.0), (100.0, 2.0), (60.0, 2.0), (60.0, 5.0), (0.0, 5.0)]


def test_clip_keeps_the_footprint_of_the_partners(client, tmp_path):
    from shapes import extrude_polygon

    handle = client.load(extrude_polygon(STEP_PROFILE, 30.0), tmp_path)
    g = graph(client, handle)
    bottom = face_with(g, "plane", lambda f: f["normal"][1] < -0.99)["id"]
    thin_top = face_with(g, "plane", lambda f: f["normal"][1] > 0.99 and f["centroid"][0] > 60)["id"]
    thick_top = face_with(g, "plane", lambda f: f["normal"][1] > 0.99 and f["centroid"][0] < 60)["id"]
    clip = {"partners": [[thin_top]], "fuzzy": 1e-6, "narrow": 2.0}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert [f["source"] for f in ok["faces"]] == [bottom]
    assert ok["faces"][0]["area"] == pytest.approx(40.0 * 30.0)
    assert ok["faces"][0]["centroid"] == pytest.approx([80.0, 1.0, 15.0])
    # Both partners cover the whole bottom: nothing to clip, the face is left as offset.
    # An uncovered band no wider than `narrow` stays (a 60 x 30 band is 2 x 1800 / 180 = 20 wide).
    clip = {"partners": [[thin_top]], "fuzzy": 1e-6, "narrow": 20.5}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert ok["faces"][0]["area"] == pytest.approx(100.0 * 30.0)
    # Given the wall: the band reaches 60 from the covered piece, past twice its width, so it goes if it lies on
    # another wall. Across it at mid-wall the material is 5 thick: more than twice a 2 mm wall, and within its
    # plane 30 across (the extrusion), a wall when walls up to 100 pair (it goes), a block when they stop at 20
    # (it stays). For a 3 mm wall, 5 across is its own wall (it stays).
    for thickness, wall_max, area in [(2.0, 100.0, 40.0 * 30.0), (2.0, 20.0, 100.0 * 30.0), (3.0, 100.0, 100.0 * 30.0)]:
        clip = {"partners": [[thin_top]], "fuzzy": 1e-6, "narrow": 20.5, "thickness": thickness, "to_mid": 0.0,
                "wall_max": wall_max}
        ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
        assert sum(f["area"] for f in ok["faces"]) == pytest.approx(area), (thickness, wall_max)
    clip = {"partners": [[thin_top, thick_top]], "fuzzy": 1e-6, "narrow": 2.0}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert ok["faces"][0]["area"] == pytest.approx(100.0 * 30.0)
    (face,) = patch_faces(client, ok["handle"])
    assert indexed_map(face, TopAbs_VERTEX).Size() == 4


# A channel whose bottom (y = 0, x 0..100) faces 2 mm tops over x 0..40 and 60..100; between them a 20 mm wide
# block stands 10 mm tall, crossing the channel.
CROSSED_PROFILE = [
    (0.0, 0.0), (100.0, 0.0), (100.0, 2.0), (60.0, 2.0), (60.0, 10.0), (40.0, 10.0), (40.0, 2.0), (0.0, 2.0)
]


def test_clip_keeps_a_narrow_piece_between_covered_ones_and_drops_one_at_a_dead_end(client, tmp_path):
    from shapes import extrude_polygon

    handle = client.load(extrude_polygon(CROSSED_PROFILE, 30.0), tmp_path)
    g = graph(client, handle)
    bottom = face_with(g, "plane", lambda f: f["normal"][1] < -0.99)["id"]
    tops = [f["id"] for f in g["faces"] if f["normal"][1] > 0.99 and f["centroid"][1] < 3.0]
    assert len(tops) == 2
    # The 20 x 30 band under the block (12 wide) lies between the two covered pieces: `narrow` decides.
    clip = {"partners": [tops], "fuzzy": 1e-6, "narrow": 12.5, "narrow_end": 2.0}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(100.0 * 30.0)
    clip = {"partners": [tops], "fuzzy": 1e-6, "narrow": 11.5, "narrow_end": 20.0}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(80.0 * 30.0)
    # With one partner the band is a dead end next to one covered piece (and the far piece another): it
    # stays only up to `narrow_end`.
    clip = {"partners": [[tops[0]]], "fuzzy": 1e-6, "narrow": 100.0, "narrow_end": 2.0}
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(40.0 * 30.0)


def test_clip_keeps_a_wide_band_between_covered_pieces_where_the_wall_runs_on_under_it(client):
    # plate_land.step: the plate's top skin (z = 3.5) over its two bottom faces, a 3.2 wide land under it between
    # them (x 48.4..51.6, z 0..1.5). The band over the land is wider than `narrow`, but at mid-wall (z = 2.5) it lies
    # in the material all along: the plate runs on through the land's root.
    handle = load_fixture(client, "plate_land.step")
    g = graph(client, handle)
    top = face_with(g, "plane", lambda f: f["normal"][2] > 0.99)
    bottoms = [f["id"] for f in g["faces"] if f["normal"][2] < -0.99 and f["centroid"][2] > 1.0]
    assert len(bottoms) == 2

    def area(narrow=2.0, **wall):
        clip = {"partners": [bottoms], "fuzzy": 1e-6, "narrow": narrow, "narrow_end": narrow, **wall}
        ok = client.ok("make_patch", handle=handle, faces=[top["id"]], offset=-1.0, clip=clip)
        return sum(f["area"] for f in ok["faces"])

    assert area(thickness=2.0, to_mid=0.0, wall_max=3.0) == pytest.approx(100.0 * 60.0)
    # Without the wall to probe, `narrow` decides.
    assert area() == pytest.approx(96.8 * 60.0)
    # Where mid-wall lies outside the material (here: told it is 2 above the patch, over the plate), the band goes.
    assert area(thickness=2.0, to_mid=2.0, wall_max=3.0) == pytest.approx(96.8 * 60.0)
    # A strict clip (narrow 0: a minor thickness level) keeps only what lies over the partners, wall or not.
    assert area(narrow=0.0, thickness=2.0, to_mid=0.0, wall_max=3.0) == pytest.approx(96.8 * 60.0)


def test_clip_keeps_a_bay_in_the_footprint_where_the_wall_runs_on_under_it(client):
    # rib_side_boss.step: a boss merges into the rib's left skin (x = 49), which stops around it: a bay 5.43
    # wide and 12 high cut into that skin from the plate, 3.74 wide as 2 x area / perimeter. The rib's right
    # skin (x = 51, 60 x 15) offset to mid-wall and clipped to the left skin's footprint: the bay is one piece
    # touching one covered piece, but along most of its boundary (three sides), and at mid-wall (x = 50) it
    # lies in the rib all over: the rib runs on through the boss's root.
    handle = load_fixture(client, "rib_side_boss.step")
    g = graph(client, handle)
    right = face_with(g, "plane", lambda f: f["normal"][0] > 0.99 and 50.0 < f["centroid"][0] < 52.0)
    left = face_with(g, "plane", lambda f: f["normal"][0] < -0.99 and f["centroid"][0] > 48.0)
    assert left["area"] < right["area"] == pytest.approx(60.0 * 15.0)

    def area(**wall):
        clip = {"partners": [[left["id"]]], "fuzzy": 1e-6, "narrow": 3.0, "narrow_end": 3.0, **wall}
        ok = client.ok("make_patch", handle=handle, faces=[right["id"]], offset=-1.0, clip=clip)
        return sum(f["area"] for f in ok["faces"])

    assert area(thickness=2.0, to_mid=0.0, wall_max=3.0) == pytest.approx(60.0 * 15.0)
    # Without the wall to probe, the bay is wider than `narrow_end` and goes.
    assert area() == pytest.approx(left["area"])
    # Where mid-wall lies outside the material (told it is 2 off the patch, out past the right skin), it goes.
    assert area(thickness=2.0, to_mid=2.0, wall_max=3.0) == pytest.approx(left["area"])


def slot_end() -> "TopoDS_Shape":
    """The end of a slot (radius 1.5 about Z, y >= 0, 10 tall) in a 2 mm half ring, which from 120 degrees on
    runs into a block (x >= -1.75): the ring's outer face (radius 3.5) spans 120..180 degrees only."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
    from OCP.gp import gp_Ax2

    axis = gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    ring = BRepPrimAPI_MakeCylinder(axis, 3.5, 10.0, math.pi).Shape()
    block = BRepPrimAPI_MakeBox(gp_Pnt(-1.75, 0, 0), gp_Pnt(6, 6, 10)).Shape()
    hole = BRepPrimAPI_MakeCylinder(axis, 1.5, 10.0).Shape()
    shape = BRepAlgoAPI_Cut(BRepAlgoAPI_Fuse(ring, block).Shape(), hole).Shape()
    unify = ShapeUpgrade_UnifySameDomain(shape, True, True, False)
    unify.Build()
    return unify.Shape()


def test_clip_drops_a_tongue_at_a_dead_end_however_narrow(client):
    # channel_low_end.step: the end wall (x 0..2, 20 high) meets side walls 40 high that end flush with its outer
    # skin, so that skin (x = 0) carries a 2 wide tongue above each corner, lying on a side wall's end.
    handle = load_fixture(client, "channel_low_end.step")
    g = graph(client, handle)
    outer = face_with(g, "plane", lambda f: f["normal"][0] < -0.99)
    inner = face_with(g, "plane", lambda f: f["normal"][0] > 0.99 and f["centroid"][0] < 50.0)
    assert outer["area"] == pytest.approx(60.0 * 20.0 + 2 * 2.0 * 20.0)

    def area(narrow_end, wall_max=3.0):
        clip = {"partners": [[inner["id"]]], "fuzzy": 1e-6, "narrow": narrow_end, "narrow_end": narrow_end,
                "thickness": 2.0, "to_mid": 0.0, "wall_max": wall_max}
        ok = client.ok("make_patch", handle=handle, faces=[outer["id"]], offset=-1.0, clip=clip)
        return sum(f["area"] for f in ok["faces"])

    # The uncovered piece (the 2 wide band round the inner skin's footprint, tongues and all) is 1.6 wide as
    # 2 x area / perimeter, but its tongues reach 20 from the footprint: past twice the dead-end width, and
    # lying on the side walls (the material across runs their length, the walls are 2 thick), it goes.
    assert area(3.0) == pytest.approx(56.0 * 18.0)
    # Within twice the dead-end width it is an overshoot, and the face stays whole.
    assert area(10.5) == pytest.approx(outer["area"])
    # Where the side walls (2 thick) are thicker than the walls that pair, no patch of theirs covers the
    # tongues: they stay.
    assert area(3.0, wall_max=1.5) == pytest.approx(outer["area"])


def test_clip_cuts_a_cylinder_to_the_sector_of_its_coaxial_partner(client, tmp_path):
    handle = client.load(slot_end(), tmp_path)
    g = graph(client, handle)
    inner = face_with(g, "cylinder", lambda f: f["surface"]["radius"] < 2)["id"]
    outer = face_with(g, "cylinder", lambda f: f["surface"]["radius"] > 3)["id"]
    # At radius 2.5 the partner's 60 degrees cover 2.62 x 10; the 120 degrees over the block (5.24 x 10,
    # 3.44 wide) are a dead end.
    clip = {"partners": [[outer]], "fuzzy": 1e-6, "narrow": 10.0, "narrow_end": 2.0}
    ok = client.ok("make_patch", handle=handle, faces=[inner], offset=-1.0, clip=clip)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(math.pi / 3 * 2.5 * 10.0, rel=1e-6)
    (face,) = patch_faces(client, ok["handle"])
    assert BRepAdaptor_Surface(face).GetType() == GeomAbs_Cylinder
    clip = {"partners": [[outer]], "fuzzy": 1e-6, "narrow": 10.0, "narrow_end": 3.5}
    ok = client.ok("make_patch", handle=handle, faces=[inner], offset=-1.0, clip=clip)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(math.pi * 2.5 * 10.0, rel=1e-6)


def pocketed_plate() -> "TopoDS_Shape":
    """A 60 x 30 x 2 plate with a 20 x 10 pocket 0.8 deep in its top (floor at z = 1.2, x 20..40, y 10..20)."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox

    plate = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(60, 30, 2)).Shape()
    pocket = BRepPrimAPI_MakeBox(gp_Pnt(20, 10, 1.2), gp_Pnt(40, 20, 3)).Shape()
    return BRepAlgoAPI_Cut(plate, pocket).Shape()


def test_clip_leaves_the_footprint_of_excluded_faces_holes_and_all_to_other_patches(client, tmp_path):
    handle = client.load(pocketed_plate(), tmp_path)
    g = graph(client, handle)
    bottom = face_with(g, "plane", lambda f: f["normal"][2] < -0.99)["id"]
    top = face_with(g, "plane", lambda f: f["normal"][2] > 0.99 and f["centroid"][2] > 1.9)["id"]
    floor = face_with(g, "plane", lambda f: f["normal"][2] > 0.99 and f["centroid"][2] < 1.9)["id"]

    def area(partners, exclude=None, narrow=100.0):
        clip = {"partners": [partners], "fuzzy": 1e-6, "narrow": narrow, "narrow_end": narrow}
        if exclude is not None:
            clip["exclude"] = [exclude]
        ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0, clip=clip)
        return sum(f["area"] for f in ok["faces"])

    # The top's outer wire covers the pocket too: alone it clips nothing.
    assert area([top]) == pytest.approx(60.0 * 30.0)
    # The 2 mm level without the pocket's footprint, however narrow a piece the clip would keep.
    assert area([top], [floor]) == pytest.approx(60.0 * 30.0 - 20.0 * 10.0)
    # The 1.2 mm level: the floor's footprint only. The top is excluded with its hole, so the pocket stays.
    assert area([floor], [top]) == pytest.approx(20.0 * 10.0)
    assert area([floor], []) == pytest.approx(60.0 * 30.0), "unexcluded, the ring round the pocket is narrow enough"


def test_clip_needs_one_partner_list_per_face(client, tmp_path):
    handle = client.load(box(40, 40, 5), tmp_path)
    err = client.err("make_patch", handle=handle, faces=[0, 1], offset=-1.0, clip={"partners": [[2]], "fuzzy": 0.0, "narrow": 1.0})
    assert err["code"] == "bad_args" and "one list per face" in err["message"]
    clip = {"partners": [[2], [3]], "fuzzy": 0.0, "narrow": 1.0, "exclude": [[4]]}
    err = client.err("make_patch", handle=handle, faces=[0, 1], offset=-1.0, clip=clip)
    assert err["code"] == "bad_args" and "clip.exclude" in err["message"]


def test_fill_removes_the_inner_loops_holding_the_given_edges(client, tmp_path):
    handle = client.load(plate_with_hole(2.0), tmp_path)
    g = graph(client, handle)
    top = face_with(g, "plane", lambda f: f["normal"][2] > 0.99)
    assert len(top["loops"]) == 2, "the hole is an inner loop of the top face"
    hole_edges = top["loops"][1]
    kept = client.ok("make_patch", handle=handle, faces=[top["id"]], offset=-2.5)
    assert kept["filled"] == 0 and kept["faces"][0]["area"] == pytest.approx(1600.0 - math.pi * 4.0)
    ok = client.ok("make_patch", handle=handle, faces=[top["id"]], offset=-2.5, fill=hole_edges)
    assert ok["filled"] == 1
    assert ok["faces"][0]["area"] == pytest.approx(1600.0)
    (face,) = patch_faces(client, ok["handle"])
    assert indexed_map(face, TopAbs_WIRE).Size() == 1
    assert BRepCheck_Analyzer(face).IsValid()
    err = client.err("make_patch", handle=handle, faces=[top["id"]], offset=-2.5, fill=[10_000])
    assert "fill edge" in err["message"]


def test_freeform_patch_reads_back_whole(client, tmp_path):
    # A mid-patch of a B-spline skin (an offset surface) written and read back: the file holds a B-spline
    # surface fitted to it within 1e-6 mm, which the reader rebuilds (it dropped the offset surface).
    converter = BRepBuilderAPI_NurbsConvert(shaft(5.0, 20.0), True)
    handle = client.load(converter.Shape(), tmp_path)
    lateral = max(graph(client, handle)["faces"], key=lambda f: f["area"])
    ok = client.ok("make_patch", handle=handle, faces=[lateral["id"]], offset=-1.0)
    path = tmp_path / "patch.step"
    written = client.ok("write_step", path=str(path), handle=ok["handle"], faces=[], check=True)
    assert written["valid"] is True and written["invalid"] == []
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    (back,) = [TopoDS.Face(f) for f in [indexed_map(reader.OneShape(), TopAbs_FACE).FindKey(1)]]
    surface = BRepAdaptor_Surface(back)
    assert surface.GetType() == GeomAbs_BSplineSurface
    assert_on_radius(surface, back, 4.0)


def test_a_dome_patch_ends_on_the_rim_plane_not_past_it(client, tmp_path):
    """A spherical shell R 30 / R 28 cut by a plane 10 above its centre: the outer sphere offset inwards by 1
    keeps its latitude bounds, so its rim would sit 1/3 mm below the rim plane, outside the solid. Cut to the
    solid, the patch ends on the plane: what lies outside goes."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
    from OCP.gp import gp_Pnt

    shell = BRepAlgoAPI_Cut(BRepPrimAPI_MakeSphere(30.0).Shape(), BRepPrimAPI_MakeSphere(28.0).Shape()).Shape()
    cap = BRepAlgoAPI_Common(shell, BRepPrimAPI_MakeBox(gp_Pnt(-40, -40, 10), gp_Pnt(40, 40, 40)).Shape()).Shape()
    handle = client.load(cap, tmp_path)
    outer = face_with(graph(client, handle), "sphere", lambda f: f["surface"]["radius"] > 29)["id"]
    ok = client.ok("make_patch", handle=handle, faces=[outer], offset=-1.0)
    (face,) = patch_faces(client, ok["handle"])
    lowest = min(z for _, _, z in vertices(face))
    assert lowest == pytest.approx(10.0, abs=1e-6)
    # The zone of the mid sphere R 29 above z = 10: 2 pi R h.
    assert ok["faces"][0]["area"] == pytest.approx(2 * math.pi * 29 * (29 - 10), rel=1e-6)


def test_a_tube_patch_ends_on_an_oblique_rim_plane_not_past_it(client):
    """tube_oblique_end: a tube R 20 / R 18 cut by a plane tilted 30 degrees. The outer cylinder offset inwards by
    1 keeps its rim's heights, so on one side the rim lies up to tan 30 = 0.58 above the cut (out of the
    material; a crescent reaching 0.37 past the cut on average, over the rim tolerance of 0.2), on the other as
    far below it. Cut to the solid, the patch reaches the plane nowhere past it; the short side is left to the
    stitching's growth to the rim."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.TopAbs import TopAbs_EDGE

    handle = load_fixture(client, "tube_oblique_end.step")
    outer = face_with(graph(client, handle), "cylinder", lambda f: f["surface"]["radius"] > 19)["id"]
    ok = client.ok("make_patch", handle=handle, faces=[outer], offset=-1.0)
    normal = (0.0, -math.sin(math.radians(30)), math.cos(math.radians(30)))
    heights = []
    for face in patch_faces(client, ok["handle"]):
        edges = indexed_map(face, TopAbs_EDGE)
        for i in range(edges.Size()):
            curve = BRepAdaptor_Curve(TopoDS.Edge(edges.FindKey(i + 1)))
            for k in range(21):
                p = curve.Value(curve.FirstParameter() + (curve.LastParameter() - curve.FirstParameter()) * k / 20)
                heights.append(dot((p.X() - 20.0, p.Y() - 20.0, p.Z() - 40.0), normal))
    assert max(heights) == pytest.approx(0.0, abs=1e-5)
    assert min(h for h in heights if h > -30) < -0.5  # the short side stays short here



def test_a_plate_patch_ends_where_its_mid_plane_meets_a_deep_chamfer(client):
    """plate_deep_chamfers: a 100 x 60 x 2 plate whose top rim is chamfered 1.5 x 45 degrees. The bottom skin runs
    to the plate's edge, but the mid-plane z = 1 meets the chamfers 0.5 inside it: the bottom's offset is cut
    there (99 x 59), not left 0.5 out of the material all round."""
    handle = load_fixture(client, "plate_deep_chamfers.step")
    bottom = face_with(graph(client, handle), "plane", lambda f: f["normal"][2] < -0.99)["id"]
    ok = client.ok("make_patch", handle=handle, faces=[bottom], offset=-1.0)
    assert sum(f["area"] for f in ok["faces"]) == pytest.approx(99.0 * 59.0, rel=1e-9)


def test_the_cut_to_the_solid_splits_by_the_faces_that_can_cut():
    """within_solid splits a curved patch face by the solid's faces near it only, and by the wall's own skins only
    where they touch it: a tube R 20 / R 18, 40 long, its outer cylinder offset to R 19. The two end rings can
    cut it; the skins lie 1 away (left out as skins, in as plain neighbours: their boxes hold the face's)."""
    from build123d import Cylinder
    from OCP.GeomAbs import GeomAbs_Cylinder
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopLoc import TopLoc_Location
    from OCP.gp import gp_Trsf, gp_Vec

    from midsurf_sidecar.geom.solid_boundary import SolidBoundary
    from midsurf_sidecar.patch.face_offset import offset_face

    tube = (Cylinder(20, 40) - Cylinder(18, 40)).wrapped
    faces = indexed_map(tube, TopAbs_FACE)
    cylinders = [TopoDS.Face(faces.FindKey(i)) for i in range(1, faces.Size() + 1)
                 if BRepAdaptor_Surface(TopoDS.Face(faces.FindKey(i))).GetType() == GeomAbs_Cylinder]
    outer = max(cylinders, key=lambda f: BRepAdaptor_Surface(f).Cylinder().Radius())
    mid = offset_face(outer, -1.0)

    def near(skins):
        found = SolidBoundary(tube).faces_near(mid, 1e-6, skins)
        return indexed_map(found, TopAbs_FACE).Size() if found is not None else 0

    assert faces.Size() == 4
    assert near([]) == 4
    assert near(cylinders) == 2
    # Moved 500 up, the face is near none of them: nothing can cut it.
    shift = gp_Trsf()
    shift.SetTranslation(gp_Vec(0.0, 0.0, 500.0))
    assert SolidBoundary(tube).faces_near(TopoDS.Face(mid.Moved(TopLoc_Location(shift))), 1e-6, []) is None


def test_the_separation_bound_never_exceeds_the_distance_and_finds_a_mid_patch_half_a_wall_from_its_skins():
    """separation_bound is a lower bound on the exact distance (BRepExtrema) for parallel planes and cylinders on
    parallel axes, 0 for other pairs: a tube R 20 / R 18 with its outer cylinder offset to R 19, the same face
    moved 0.3 off the axis, and a box's faces."""
    from build123d import Box, Cylinder
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.GeomAbs import GeomAbs_Cylinder
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopLoc import TopLoc_Location
    from OCP.gp import gp_Trsf, gp_Vec

    from midsurf_sidecar.geom.solid_boundary import separation_bound
    from midsurf_sidecar.patch.face_offset import offset_face

    def faces_of(shape):
        found = indexed_map(shape, TopAbs_FACE)
        return [TopoDS.Face(found.FindKey(i)) for i in range(1, found.Size() + 1)]

    def moved(face, x):
        shift = gp_Trsf()
        shift.SetTranslation(gp_Vec(x, 0.0, 0.0))
        return TopoDS.Face(face.Moved(TopLoc_Location(shift)))

    tube = faces_of((Cylinder(20, 40) - Cylinder(18, 40)).wrapped)
    cylinders = [f for f in tube if BRepAdaptor_Surface(f).GetType() == GeomAbs_Cylinder]
    outer, inner = sorted(cylinders, key=lambda f: -BRepAdaptor_Surface(f).Cylinder().Radius())
    mid = offset_face(outer, -1.0)
    assert separation_bound(mid, outer) == pytest.approx(1.0, abs=1e-6)
    assert separation_bound(mid, inner) == pytest.approx(1.0, abs=1e-6)
    assert separation_bound(moved(mid, 0.3), outer) == pytest.approx(0.7, abs=1e-6)
    box = faces_of(Box(10, 20, 30).wrapped)
    planes = [(a, b) for a in box for b in box if not a.IsSame(b)]
    pairs = [(mid, f) for f in tube] + [(moved(mid, 0.3), outer)] + planes + [(mid, box[0])]
    for a, b in pairs:
        exact = BRepExtrema_DistShapeShape(a, b).Value()
        assert separation_bound(a, b) <= exact + 1e-9
    # Opposite sides of the box: their separation; adjacent sides and mixed kinds: no bound.
    assert sorted(round(separation_bound(a, b), 6) for a, b in planes if separation_bound(a, b) > 0) == sorted(
        [10.0, 10.0, 20.0, 20.0, 30.0, 30.0])
    assert separation_bound(mid, box[0]) == 0.0
