"""fuse: patches split at their mutual intersections, crossing edges shared, faces traced to their patch."""

from collections import Counter
from pathlib import Path

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_FACE, TopAbs_VERTEX
from OCP.TopoDS import TopoDS

from midsurf_sidecar.fuse.patch_fuse import _chain_through
from midsurf_sidecar.geom.booleans import general_fuse
from midsurf_sidecar.geom.topology import indexed_map, subshapes
from patch_shapes import compound, horizontal, put_patches, rectangle, vertical
from shapes import bent_sheet

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def fuse(client, patches, fuzzy=1e-6):
    fused = client.ok("fuse", patches=patches, fuzzy=fuzzy)
    check_consistent(fused)
    return fused


def check_consistent(fused):
    """Faces' `edges` and edges' `faces` describe the same incidences; 5 points per edge."""
    from_faces = Counter((e, i) for i, face in enumerate(fused["faces"]) for e in face["edges"])
    from_edges = Counter((e, i) for e, edge in enumerate(fused["edges"]) for i in edge["faces"])
    assert from_faces == from_edges
    assert max(from_faces.values(), default=1) == 1
    for edge in fused["edges"]:
        assert len(edge["points"]) == 5
        assert edge["faces"] == sorted(edge["faces"])


def on_line(edge, **fixed):
    """Whether all points of the edge have the given coordinates (x=, y=, z=)."""
    axes = {"x": 0, "y": 1, "z": 2}
    return all(p[axes[k]] == pytest.approx(v, abs=1e-7) for p in edge["points"] for k, v in fixed.items())


def test_l_corner_crossing_is_shared_by_four_faces(client):
    fused = fuse(client, put_patches(client, horizontal(), vertical(1.0)))
    faces = fused["faces"]
    pieces = sorted((f["patch"], round(f["area"], 6)) for f in faces)
    assert pieces == [(0, 40), (0, 2360), (1, 40), (1, 1560)]
    for face in faces:
        assert face["normal"] == pytest.approx([0, 0, 1] if face["patch"] == 0 else [1, 0, 0], abs=1e-12)
    crossing = [e for e in fused["edges"] if len(e["faces"]) == 4]
    assert len(crossing) == 1
    (edge,) = crossing
    assert edge["faces"] == [0, 1, 2, 3]
    assert edge["length"] == pytest.approx(40.0)
    ys = sorted(p[1] for p in edge["points"])
    assert ys == pytest.approx([0, 10, 20, 30, 40])
    assert on_line(edge, x=1.0, z=1.0)
    assert all(len(e["faces"]) == 1 for e in fused["edges"] if e is not edge)
    shape = client.session.store.get(fused["handle"])
    assert indexed_map(shape, TopAbs_FACE).Size() == 4
    assert BRepCheck_Analyzer(shape).IsValid()


def test_plates_apart_stay_whole(client):
    far = rectangle((0, 0, 10), (6, 0, 10), (6, 4, 10), (0, 4, 10))
    fused = fuse(client, put_patches(client, horizontal(), far))
    assert [f["patch"] for f in fused["faces"]] == [0, 1]
    assert [f["area"] for f in fused["faces"]] == pytest.approx([2400, 24])
    assert len(fused["edges"]) == 8
    assert all(len(e["faces"]) == 1 for e in fused["edges"])


def test_t_junction_splits_the_base_and_shares_the_foot(client):
    fused = fuse(client, put_patches(client, horizontal(), vertical(30.0, z0=1.0)))
    pieces = sorted((f["patch"], round(f["area"], 6)) for f in fused["faces"])
    assert pieces == [(0, 1200), (0, 1200), (1, 1560)]
    (foot,) = [e for e in fused["edges"] if len(e["faces"]) == 3]
    assert foot["length"] == pytest.approx(40.0)
    assert on_line(foot, x=30.0, z=1.0)
    assert Counter(len(e["faces"]) for e in fused["edges"]) == {1: 9, 3: 1}


def test_patches_of_different_bodies_are_fused_apart(client):
    # The T of the test above, its two patches in two bodies: neither splits the other, nothing is shared; the
    # third patch, of the first body, still splits the base where it crosses it.
    third = vertical(45.0, z0=1.0)
    handles = put_patches(client, horizontal(), vertical(30.0, z0=1.0), third)
    fused = client.ok("fuse", patches=handles, fuzzy=1e-6, bodies=[0, 5, 0])
    check_consistent(fused)
    pieces = sorted((f["patch"], round(f["area"], 6)) for f in fused["faces"])
    assert pieces == [(0, 600), (0, 1800), (1, 1560), (2, 1560)]
    assert Counter(len(e["faces"]) for e in fused["edges"]) == {1: 6 + 3 + 4, 3: 1}
    (foot,) = [e for e in fused["edges"] if len(e["faces"]) == 3]
    assert on_line(foot, x=45.0, z=1.0)
    # Faces follow the bodies in order of their first patches: body 0's pieces, then body 5's.
    assert [f["patch"] for f in fused["faces"]][-1] == 1
    assert BRepCheck_Analyzer(client.session.store.get(fused["handle"])).IsValid()


def test_fuzzy_closes_a_small_gap(client):
    gap = 1e-5
    lifted = vertical(30.0, z0=1.0 + gap)
    apart = fuse(client, put_patches(client, horizontal(), lifted), fuzzy=0.0)
    assert len(apart["faces"]) == 2
    joined = fuse(client, put_patches(client, horizontal(), lifted), fuzzy=1e-4)
    assert len(joined["faces"]) == 3
    assert max(len(e["faces"]) for e in joined["edges"]) == 3


def test_overlap_goes_to_the_lower_patch(client):
    # Coplanar patches overlapping on x 30..60: the common piece is one face, credited to patch 0.
    shifted = rectangle((30, 0, 1), (90, 0, 1), (90, 40, 1), (30, 40, 1))
    for patches, pieces in (((horizontal(), shifted), [0, 0, 1]), ((shifted, horizontal()), [0, 0, 1])):
        fused = fuse(client, put_patches(client, *patches))
        assert sorted(f["patch"] for f in fused["faces"]) == pieces
        assert [f["area"] for f in fused["faces"]] == pytest.approx([1200] * 3)
    same = fuse(client, put_patches(client, horizontal(), horizontal()))
    assert [(f["patch"], f["area"]) for f in same["faces"]] == [(0, pytest.approx(2400))]


def test_faces_of_one_patch_share_their_common_edges(client, tmp_path):
    # The outer skin of the bend (plane, cylinder, plane) offset face by face: one patch of 3 faces
    # that only touch; the fuse makes their common edges shared.
    handle = client.load(bent_sheet(), tmp_path)
    patch = client.ok("make_patch", handle=handle, faces=[0, 1, 2], offset=-1.0)["handle"]
    fused = fuse(client, [patch], fuzzy=1e-4)
    assert [f["patch"] for f in fused["faces"]] == [0, 0, 0]
    shared = [e for e in fused["edges"] if len(e["faces"]) == 2]
    assert len(shared) == 2
    assert all(e["length"] == pytest.approx(10.0) for e in shared)


def test_no_patches_give_an_empty_compound(client):
    fused = client.ok("fuse", patches=[], fuzzy=1e-4)
    assert fused["faces"] == [] and fused["edges"] == []
    shape = client.session.store.get(fused["handle"])
    assert shape.ShapeType() == TopAbs_COMPOUND
    assert indexed_map(shape, TopAbs_FACE).Size() == 0


def test_a_single_face_comes_back_as_is(client):
    fused = fuse(client, put_patches(client, horizontal()))
    assert [(f["patch"], f["area"]) for f in fused["faces"]] == [(0, pytest.approx(2400))]
    assert len(fused["edges"]) == 4 and all(e["faces"] == [0] for e in fused["edges"])


def test_open_box_mid_walls_share_every_crossing(client):
    handle = client.ok("load_step", path=str(FIXTURES / "open_box_ribs.step"))["solids"][0]["handle"]
    # 80 x 60 x 30 open box, 2 mm walls: outer faces x=0, y=0, y=60, z=0, x=80 -> mid-planes at 1 mm.
    outer = [0, 1, 3, 4, 5]
    patches = [client.ok("make_patch", handle=handle, faces=[i], offset=-1.0) for i in outer]
    fused = fuse(client, [p["handle"] for p in patches], fuzzy=1e-4)
    assert BRepCheck_Analyzer(client.session.store.get(fused["handle"])).IsValid()
    # Each patch is cut into pieces that add up to it.
    for k, patch in enumerate(patches):
        pieces = sum(f["area"] for f in fused["faces"] if f["patch"] == k)
        assert pieces == pytest.approx(patch["faces"][0]["area"])
    # Every wall/bottom and wall/wall crossing runs its full length as X edges (4 faces).
    crossings = [
        ({"x": 1, "z": 1}, 60), ({"x": 79, "z": 1}, 60), ({"y": 1, "z": 1}, 80), ({"y": 59, "z": 1}, 80),
        ({"x": 1, "y": 1}, 30), ({"x": 1, "y": 59}, 30), ({"x": 79, "y": 1}, 30), ({"x": 79, "y": 59}, 30),
    ]
    for line, length in crossings:
        on = [e for e in fused["edges"] if on_line(e, **line)]
        assert all(len(e["faces"]) == 4 for e in on), line
        assert sum(e["length"] for e in on) == pytest.approx(length), line
    assert Counter(len(e["faces"]) for e in fused["edges"])[4] == 20


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ({"patches": "all", "fuzzy": 1e-4}, "`patches`"),
        ({"patches": [0], "fuzzy": 1e-4}, "`patches`"),
        ({"patches": [99], "fuzzy": 1e-4}, "no shape with handle 99"),
        ({"fuzzy": 1e-4}, "`patches`"),
        ({"patches": []}, "`fuzzy`"),
        ({"patches": [], "fuzzy": -1e-4}, "`fuzzy` must be >= 0"),
        ({"patches": [], "fuzzy": "tight"}, "`fuzzy`"),
        ({"patches": [], "fuzzy": 1e-4, "bodies": [0]}, "`bodies`"),
        ({"patches": [], "fuzzy": 1e-4, "bodies": "all"}, "`bodies`"),
    ],
)
def test_bad_arguments(client, args, needle):
    err = client.err("fuse", **args)
    assert err["code"] == "bad_args"
    assert needle in err["message"]


def test_repeated_patch_is_bad_args(client):
    (patch,) = put_patches(client, horizontal())
    err = client.err("fuse", patches=[patch, patch], fuzzy=1e-4)
    assert err["code"] == "bad_args" and str(patch) in err["message"]


def bow_tie(z: float):
    """A face at height z over x, y in [0, 60] x [0, 40] whose wire crosses itself: a face OCCT cannot split
    without losing its area (as a strip grown across a fillet's edge can come out)."""
    return rectangle((0, 0, z), (60, 40, z), (60, 0, z), (0, 40, z))


def test_a_fuse_whose_pieces_lose_area_fails(client):
    # A T of a wall on a plate, the wall carrying a broken face across it: OCCT splits it without an error but
    # its pieces do not cover it, and the fuse says so rather than hand on patches with material missing.
    wall, broken = vertical(30.0, z0=1.0), bow_tie(20.0)
    plate, grown, other = put_patches(client, horizontal(), compound(wall, broken), vertical(45.0, z0=1.0))
    err = client.err("fuse", patches=[plate, grown, other], fuzzy=1e-6)
    assert err["code"] == "kernel_error" and "lost" in err["message"]
    fused = client.ok("fuse", patches=[plate, put_patches(client, compound(wall))[0], other], fuzzy=1e-6)
    check_consistent(fused)


def c_shaped_boss(z0: float):
    """A cylinder r = 5 about x = 30, y = 20, three quarters of a turn, standing on z = z0 up to 10."""
    import math

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt

    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(30, 20, z0), gp_Dir(0, 0, 1)), 5.0)
    return BRepBuilderAPI_MakeFace(surface, 0.0, 1.5 * math.pi, 0.0, 10.0 - z0, 1e-7).Face()


def test_a_boss_foot_arc_inside_a_face_is_a_boundary_edge_after_split_internal(client):
    # The C-shaped boss's foot ends inside the base: an INTERNAL edge there, which STEP drops (the boss would
    # be written loose). Completed to its circle, it cuts a disc out of the base and is shared by all three.
    handles = put_patches(client, horizontal(), c_shaped_boss(1.0))
    fused = client.ok("fuse", patches=handles, fuzzy=1e-6, split_internal=True)
    check_consistent(fused)
    pieces = sorted((f["patch"], round(f["area"], 6)) for f in fused["faces"])
    disc = round(3.141592653589793 * 25, 6)
    assert pieces == [(0, disc), (0, round(2400 - disc, 6)), (1, round(1.5 * 3.141592653589793 * 5 * 9, 6))]
    (foot,) = [e for e in fused["edges"] if len(e["faces"]) == 3]
    assert foot["length"] == pytest.approx(1.5 * 3.141592653589793 * 5)
    assert all(p[2] == pytest.approx(1.0) for p in foot["points"])


def test_a_rib_foot_on_a_curved_face_splits_it_along_the_rib_plane(client):
    """A flat rib standing part way across a cylindrical panel, at a slant to its axis: its foot is an ellipse's
    arc (not a line, not a circle) ending inside the panel, an INTERNAL edge there. The section of the panel
    with the rib's plane completes it through to the panel's boundary, so the foot is a boundary edge shared by
    the two panel pieces and the rib."""
    import math

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt

    # A panel on the cylinder R 50 about the y axis (z up to 50 at x = 0), x from -30 to 30 round it, y 0..40.
    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0), gp_Dir(-1, 0, 0)), 50.0)
    half = math.asin(30.0 / 50.0)
    panel = BRepBuilderAPI_MakeFace(surface, math.pi / 2 - half, math.pi / 2 + half, 0.0, 40.0, 1e-7).Face()
    # The rib: in the plane x + y = 20, x from 0 to 10, from z = 45 (below the panel) up to 60.
    rib = rectangle((0, 20, 45), (10, 10, 45), (10, 10, 60), (0, 20, 60))
    handles = put_patches(client, panel, rib)
    fused = client.ok("fuse", patches=handles, fuzzy=1e-6, split_internal=True)
    check_consistent(fused)
    panel_pieces = [f for f in fused["faces"] if f["patch"] == 0]
    assert len(panel_pieces) == 2
    assert sum(f["area"] for f in panel_pieces) == pytest.approx(2 * half * 50 * 40)
    feet = [e for e in fused["edges"] if len(e["faces"]) >= 3]
    assert feet and all(p[0] + p[1] == pytest.approx(20.0) for e in feet for p in e["points"])


def test_a_stem_section_is_cut_only_along_the_chain_through_the_joint():
    # The stem's surface crosses the face twice (two lines, as a plane crosses a half tube); the joint lies on
    # the first, made of two edges end to end: only those two are kept.
    def edge(a, b):
        return BRepBuilderAPI_MakeEdge(gp_Pnt(*a), gp_Pnt(*b)).Edge()

    first = [edge((0, 0, 0), (10, 0, 0)), edge((10, 0, 0), (20, 0, 0))]
    second = edge((0, 5, 0), (20, 5, 0))
    section = general_fuse([*first, second], 1e-6).Shape()  # the two halves of the first share their vertex
    joint = edge((2, 0, 0), (8, 0, 0))
    chain = _chain_through(section, joint)
    assert len(chain) == 2
    assert all(abs(BRep_Tool.Pnt_s(TopoDS.Vertex(v)).Y()) < 1e-9 for e in chain for v in subshapes(e, TopAbs_VERTEX))


def test_a_foot_ending_inside_a_face_is_an_edge_inside_it(client):
    # A wall standing on the plate with its foot (x = 30, y 10..30) inside the plate: the plate cannot be split
    # along it, and holds it as an INTERNAL edge, which a STEP file drops.
    strip = rectangle((30, 10, 1), (30, 30, 1), (30, 30, 40), (30, 10, 40))
    fused = fuse(client, put_patches(client, horizontal(), strip))
    plate = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 0]
    assert len(plate) == 1
    (foot,) = [e for e in fused["edges"] if on_line(e, x=30.0, z=1.0)]
    assert foot["inside"] == plate
    assert sorted(fused["faces"][i]["patch"] for i in foot["faces"]) == [0, 1]
    assert all("inside" not in e for e in fused["edges"] if e is not foot)


def test_settled_patches_and_the_faces_of_a_fused_patch_are_not_intersected_with_each_other(client):
    # A horizontal plate and a wall crossing it, never fused: as loose faces they split each other; as two
    # settled patches, or as two faces of one patch marked as fused, they are taken as already split, so they
    # stay whole (the caller's promise is what makes a stitching pass's fuse cheap). A patch that is neither
    # still splits the plate. (A far plate makes a second argument where one alone would be refused.)
    crossing, far = vertical(30.0), rectangle((0, 0, 90), (6, 0, 90), (6, 4, 90), (0, 4, 90))
    plain = fuse(client, put_patches(client, horizontal(), crossing))
    assert len(plain["faces"]) == 4
    trusted = client.ok("fuse", patches=put_patches(client, horizontal(), crossing, far), fuzzy=1e-6, settled=[0, 1])
    assert sorted(round(f["area"]) for f in trusted["faces"]) == [24, 1600, 2400]
    one_patch = client.session.store.put(compound(horizontal(), crossing))
    handles = [one_patch, client.session.store.put(compound(far))]
    assert len(client.ok("fuse", patches=handles, fuzzy=1e-6)["faces"]) == 5
    assert len(client.ok("fuse", patches=handles, fuzzy=1e-6, patches_fused=True)["faces"]) == 3
    third = client.session.store.put(compound(vertical(45.0, z0=1.0)))
    handles = put_patches(client, horizontal(), crossing) + [third]
    mixed = client.ok("fuse", patches=handles, fuzzy=1e-6, settled=[0, 1])
    check_consistent(mixed)
    assert sorted((f["patch"], round(f["area"])) for f in mixed["faces"]) == [(0, 600), (0, 1800), (1, 1600), (2, 1560)]


def test_a_tube_ending_inside_a_wall_parts_the_wall_at_its_end(client):
    """A tube (a screw boss, R 5 about x = 30, y = 2, z 0..25) crossing a wall (y = 0, x 0..60, z 0..40) that
    runs on above it: the tube's two lines on the wall end inside it, abreast. Extended, they part the wall's
    stretch inside the tube; the cut between their ends parts that stretch again where the tube ends, so the
    wall inside the tube's wall below its end is a piece of its own."""
    import math

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir

    wall = rectangle((0, 0, 0), (60, 0, 0), (60, 0, 40), (0, 0, 40))
    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(30, 2, 0), gp_Dir(0, 0, 1)), 5.0)
    tube = BRepBuilderAPI_MakeFace(surface, 0.0, 2 * math.pi, 0.0, 25.0, 1e-7).Face()
    fused = client.ok("fuse", patches=put_patches(client, wall, tube), fuzzy=1e-6, split_internal=True)
    check_consistent(fused)
    chord = 2 * math.sqrt(5.0**2 - 2.0**2)
    side = (60 - chord) / 2 * 40
    pieces = sorted(round(f["area"], 6) for f in fused["faces"] if f["patch"] == 0)
    assert pieces == pytest.approx(sorted([side, side, chord * 25, chord * 15]))
    wall_only = [e for e in fused["edges"] if all(fused["faces"][f]["patch"] == 0 for f in e["faces"])]
    (cut,) = [e for e in wall_only if len(e["faces"]) == 2 and on_line(e, z=25.0)]
    assert cut["length"] == pytest.approx(chord)
    assert cut.get("stem_end") is True
    assert sum(1 for e in fused["edges"] if e.get("stem_end")) == 1


@pytest.mark.parametrize("stem", ["half_tube_on_one_side", "flat_strips_across"])
def test_only_a_tube_crossing_a_wall_is_cut_across_at_its_end(client, stem):
    """Two lines ending inside a wall (y = 0, x 0..60, z 0..40) abreast at z = 25, from stems that hold no part of
    the wall inside their own wall: a half tube standing on one side of it (R 5 about x = 30, y = 0: a U-shaped
    boss against a wall), and two flat strips crossing it (x = 27 and 33, y -10..10: a box's walls)."""
    import math

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir

    wall = rectangle((0, 0, 0), (60, 0, 0), (60, 0, 40), (0, 0, 40))
    if stem == "half_tube_on_one_side":
        surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(30, 0, 0), gp_Dir(0, 0, 1)), 5.0)
        shape = compound(BRepBuilderAPI_MakeFace(surface, 0.0, math.pi, 0.0, 25.0, 1e-7).Face())
        between = 10.0
    else:
        shape = compound(
            rectangle((27, -10, 0), (27, 10, 0), (27, 10, 25), (27, -10, 25)),
            rectangle((33, -10, 0), (33, 10, 0), (33, 10, 25), (33, -10, 25)),
        )
        between = 6.0
    handles = [client.session.store.put(compound(wall)), client.session.store.put(shape)]
    fused = client.ok("fuse", patches=handles, fuzzy=1e-6, split_internal=True)
    check_consistent(fused)
    pieces = sorted(round(f["area"], 6) for f in fused["faces"] if f["patch"] == 0)
    side = (60 - between) / 2 * 40
    assert pieces == pytest.approx([between * 40, side, side])
    assert not any(e.get("stem_end") for e in fused["edges"])
