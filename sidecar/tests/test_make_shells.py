"""make_shells: shells of fused faces in one compound; shared edges survive a STEP round trip."""

import math
from pathlib import Path

import pytest

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakePolygon,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_NurbsConvert,
)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools
from OCP.collections import IndexedDataMap_TopoDS_Shape_List_TopoDS_Shape_TopTools_ShapeMapHasher as EdgeFaces
from OCP.GProp import GProp_GProps
from OCP.gp import gp, gp_Ax2, gp_Ax3, gp_Circ, gp_Cylinder, gp_Pln, gp_Pnt
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS, TopoDS_Shape

from midsurf_sidecar.geom.topology import indexed_map, subshapes
from midsurf_sidecar.write import shells
from patch_shapes import horizontal, put_patches, rectangle, vertical

DATA = Path(__file__).parent / "data"


def fused(client, *faces):
    return client.ok("fuse", patches=put_patches(client, *faces), fuzzy=1e-6)


def big_faces(fuse_reply, min_area=100.0):
    return [i for i, f in enumerate(fuse_reply["faces"]) if f["area"] > min_area]


def read_step(path):
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    return reader.OneShape()


def faces_per_edge(shape):
    """How many faces use each edge, as a sorted list."""
    ancestors = EdgeFaces()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, ancestors)
    return sorted(ancestors.FindFromIndex(i + 1).Size() for i in range(ancestors.Size()))


def face_areas(shape):
    faces = indexed_map(shape, TopAbs_FACE)
    areas = []
    for i in range(faces.Size()):
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(faces.FindKey(i + 1), props)
        areas.append(props.Mass())
    return areas


def test_l_corner_shell_keeps_its_shared_edge_through_step(client, tmp_path):
    f = fused(client, horizontal(), vertical(1.0))
    pair = big_faces(f)
    assert len(pair) == 2
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[pair])
    assert sorted(ok["faces"]) == sorted(pair)
    assert ok["valid"] is True
    shells = client.session.store.get(ok["handle"])
    assert shells.ShapeType() == TopAbs_COMPOUND
    assert indexed_map(shells, TopAbs_SHELL).Size() == 1

    path = tmp_path / "l.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    back = read_step(path)
    assert indexed_map(back, TopAbs_SHELL).Size() == 1
    assert indexed_map(back, TopAbs_FACE).Size() == 2
    assert faces_per_edge(back) == [1] * 6 + [2]


def test_faces_are_numbered_like_the_shells_shape(client):
    f = fused(client, horizontal(), vertical(30.0, z0=1.0))
    areas = [face["area"] for face in f["faces"]]
    base = [i for i, face in enumerate(f["faces"]) if face["patch"] == 0]
    wall = [i for i, face in enumerate(f["faces"]) if face["patch"] == 1]
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[wall, list(reversed(base))])
    assert sorted(ok["faces"]) == sorted(base + wall)
    shells = client.session.store.get(ok["handle"])
    assert indexed_map(shells, TopAbs_SHELL).Size() == 2
    # faces[j] is the F-index of face j of S (MapShapes order): same face, same area.
    assert face_areas(shells) == pytest.approx([areas[i] for i in ok["faces"]])
    assert ok["valid"] is True


def test_t_junction_in_one_shell_stays_non_manifold(client, tmp_path):
    f = fused(client, horizontal(), vertical(30.0, z0=1.0))
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[[0, 1, 2]])
    assert ok["valid"] is True
    path = tmp_path / "t.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    back = read_step(path)
    assert indexed_map(back, TopAbs_FACE).Size() == 3
    assert faces_per_edge(back).count(3) == 1


def test_disconnected_faces_listed_in_one_shell_become_one_shell_each(client):
    # A shell whose faces share no edge fails BRepCheck (NotConnected): each connected group is its own shell.
    far = rectangle((0, 0, 10), (6, 0, 10), (6, 4, 10), (0, 4, 10))
    f = fused(client, horizontal(), far)
    one = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[[0, 1]])
    assert one["shells"] == 2 and one["valid"] is True and one["invalid"] == []
    two = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[[0], [1]])
    assert two["shells"] == 2 and two["valid"] is True


def test_no_shells_give_an_empty_compound_that_writes(client, tmp_path):
    f = fused(client, horizontal(), vertical(1.0))
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[])
    assert ok["faces"] == [] and ok["valid"] is True
    path = tmp_path / "empty.step"
    assert client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])["bytes"] > 0
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone


@pytest.mark.parametrize(
    ("shells", "needle"),
    [
        ([[4]], "face 4 out of range"),
        ([[-1]], "face -1 out of range"),
        ([[0, 0]], "face 0 is listed twice"),
        ([[0, 1], [1, 2]], "face 1 is in shells 0 and 1"),
        ([[0], []], "shell 1 is empty"),
        ([[0.5]], "integers"),
        ([3], "must be a list"),
        ("all", "`shells`"),
    ],
)
def test_bad_arguments(client, shells, needle):
    f = fused(client, horizontal(), vertical(1.0))
    err = client.err("make_shells", handle=f["handle"], fuzzy=1e-6, shells=shells)
    assert err["code"] == "bad_args"
    assert needle in err["message"]


@pytest.mark.parametrize("handle", [0, -3, 99])
def test_bad_handles(client, handle):
    assert client.err("make_shells", handle=handle, fuzzy=1e-6, shells=[])["code"] == "bad_args"


def tube_and_lid():
    """A closed tube face (radius 10, height 20, seam at angle 0) and a plane disc face closing its top."""
    tube = BRepBuilderAPI_MakeFace(gp_Cylinder(gp_Ax3(), 10.0), 0.0, 2 * math.pi, 0.0, 20.0).Face()
    rim = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 20), gp.DZ_s()), 10.0)).Edge()
    lid = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 20), gp.DZ_s()), BRepBuilderAPI_MakeWire(rim).Wire()).Face()
    return tube, lid


def test_a_closed_tube_is_split_at_its_seam_so_no_edge_is_used_by_one_face_inside(client):
    tube, lid = tube_and_lid()
    f = fused(client, tube, lid)
    seam = [e for e in f["edges"] if len(e["faces"]) == 2 and e["faces"][0] == e["faces"][1]]
    assert len(seam) == 1, "the fuse lists the seam's face twice: it is no free edge"
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[list(range(len(f["faces"])))])
    assert ok["valid"] is True
    shells = client.session.store.get(ok["handle"])
    assert len(ok["faces"]) == 3, "tube halves and lid"
    assert sorted(ok["faces"]) == [0, 0, 1] or sorted(ok["faces"]) == [0, 1, 1]
    # Free edges only at the tube's open bottom (split in two); seam, isoline and rim are shared.
    per_edge = faces_per_edge(shells)
    assert per_edge.count(1) == 2 and all(n == 2 for n in per_edge if n != 1)
    assert sum(face_areas(shells)) == pytest.approx(2 * math.pi * 10 * 20 + math.pi * 100)


def test_a_tube_closed_on_itself_as_a_non_periodic_b_spline_is_split_at_its_seam_too(client):
    # The tube of the test above as some CAD writes it: a B-spline closed round but not periodic. Its seam bounds
    # it twice all the same, and is shared once the face is split halfway round.
    tube, lid = tube_and_lid()
    converted = subshapes(BRepBuilderAPI_NurbsConvert(tube, True).Shape(), TopAbs_FACE)[0]
    surface = BRep_Tool.Surface_s(TopoDS.Face(converted)).Copy()
    surface.SetUNotPeriodic()
    assert surface.IsUClosed() and not surface.IsUPeriodic()
    closed = BRepBuilderAPI_MakeFace(surface, 1e-7).Face()
    f = fused(client, closed, lid)
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[list(range(len(f["faces"])))])
    assert ok["valid"] is True and len(ok["faces"]) == 3, "tube halves and lid"
    per_edge = faces_per_edge(client.session.store.get(ok["handle"]))
    assert per_edge.count(1) == 2 and all(n == 2 for n in per_edge if n != 1)


def test_a_tube_cut_through_its_seam_has_no_seam_left(client):
    # A plane through the axis and the seam splits the tube into two halves, each using the old seam edge once:
    # that edge is a boundary shared by the halves (and the plane), never listed as a face joined to itself.
    tube, _ = tube_and_lid()
    cut = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp.DY_s()), -30.0, 30.0, -30.0, 30.0).Face()
    f = fused(client, tube, cut)
    assert not [e for e in f["edges"] if len(e["faces"]) != len(set(e["faces"]))]
    seam_line = [e for e in f["edges"] if all(abs(p[0] - 10.0) < 1e-6 and abs(p[1]) < 1e-6 for p in e["points"])]
    assert seam_line and all(len(set(e["faces"])) == 3 for e in seam_line), seam_line


def elliptic_wall(z0: float):
    """An elliptic wall (semi-axes 8 and 4 about x = 30, y = 20), three quarters round, from z = z0 up to 10:
    its foot on the base is neither a line nor a circle, so splitting the base along it cannot close it."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Dir, gp_Elips, gp_Vec

    ellipse = gp_Elips(gp_Ax2(gp_Pnt(30, 20, z0), gp_Dir(0, 0, 1)), 8.0, 4.0)
    foot = BRepBuilderAPI_MakeEdge(ellipse, 0.0, 1.5 * math.pi).Edge()
    return BRepPrimAPI_MakePrism(foot, gp_Vec(0, 0, 10.0 - z0)).Shape()


def test_faces_joined_only_through_an_internal_edge_are_written_as_separate_valid_shells(client, tmp_path):
    # The wall's foot stays an INTERNAL edge of the base; a STEP file keeps no internal edge, so one shell of both
    # would read back with faces not connected (BRepCheck: NotConnected). Two shells read back valid.
    f = client.ok("fuse", patches=put_patches(client, horizontal(), elliptic_wall(1.0)), fuzzy=1e-6, split_internal=True)
    every = list(range(len(f["faces"])))
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[every])
    assert ok["shells"] == 2 and ok["valid"] is True
    path = tmp_path / "mid.step"
    client.ok("write_step", handle=ok["handle"], path=str(path), faces=[])
    back = read_step(path)
    assert indexed_map(back, TopAbs_SHELL).Size() == 2
    assert BRepCheck_Analyzer(back).IsValid()


def explored_and_distinct_faces(shape):
    """(faces met by TopExp_Explorer, distinct faces): a reader that puts one face into two shells counts twice."""
    from OCP.TopExp import TopExp_Explorer

    explorer, met = TopExp_Explorer(shape, TopAbs_FACE), 0
    while explorer.More():
        met += 1
        explorer.Next()
    return met, indexed_map(shape, TopAbs_FACE).Size()


def edge_components(shape):
    """Groups of faces connected through shared edges (the judge's `components`)."""
    ancestors = EdgeFaces()
    TopExp.MapShapesAndAncestors_s(shape, TopAbs_EDGE, TopAbs_FACE, ancestors)
    faces = indexed_map(shape, TopAbs_FACE)
    parent = list(range(faces.Size()))

    def root(a):
        while parent[a] != a:
            a = parent[a]
        return a

    for i in range(ancestors.Size()):
        ids = sorted({faces.FindIndex(f) - 1 for f in ancestors.FindFromIndex(i + 1)})
        for b in ids[1:]:
            parent[root(b)] = root(ids[0])
    return len({root(i) for i in range(faces.Size())})


def test_t_joints_are_written_as_manifold_shells_that_read_back_whole(client, tmp_path):
    # A floor with two walls standing on it: two T-joint edges of three faces each. The STEP reader splits a
    # non-manifold shell itself, and then put one face into two shells or left a shell whose faces do not meet.
    # Manifold shells in one surface model read back as written: each face once, one piece, valid.
    f = fused(client, horizontal(), vertical(20.0, z0=1.0), vertical(40.0, z0=1.0))
    every = list(range(len(f["faces"])))
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[every])
    assert ok["valid"] is True and ok["shells"] >= 2 and ok["components"] == 1
    written = client.session.store.get(ok["handle"])
    shells = indexed_map(written, TopAbs_SHELL)
    for k in range(shells.Size()):
        assert max(faces_per_edge(shells.FindKey(k + 1))) <= 2, "each shell is manifold"
    path = tmp_path / "tt.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    assert path.read_text(encoding="latin-1").count("SHELL_BASED_SURFACE_MODEL") == 1
    back = read_step(path)
    assert explored_and_distinct_faces(back) == (len(every), len(every))
    assert edge_components(back) == 1
    assert faces_per_edge(back).count(3) == 2
    assert BRepCheck_Analyzer(back).IsValid()


def test_a_merge_set_becomes_one_face_and_keeps_its_edges_shared(client, tmp_path):
    # Two coplanar pieces side by side (one patch's, say a strip grown from its edge), the second meeting a wall
    # in an L: merged into one face, still sharing the L's edge with the wall once written.
    left = rectangle((0, 0, 1), (10, 0, 1), (10, 40, 1), (0, 40, 1))
    right = rectangle((10, 0, 1), (20, 0, 1), (20, 40, 1), (10, 40, 1))
    f = fused(client, left, right, vertical(20.0, z0=1.0))
    pieces = {face["patch"]: i for i, face in enumerate(f["faces"])}
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[list(range(3))],
                   merge=[[pieces[0], pieces[1]]])
    assert len(ok["faces"]) == 2 and ok["valid"] is True
    assert sorted(ok["faces"]) == sorted([pieces[0], pieces[2]])
    path = tmp_path / "merged.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    back = read_step(path)
    assert sorted(round(a) for a in face_areas(back)) == [800, 1560]
    assert edge_components(back) == 1


def test_a_merge_set_going_all_the_way_round_a_tube_stays_as_its_pieces(client):
    # Two half tubes joined along both sides: merged, they would make a face closed on itself again, its seam
    # used by that face alone (a free edge to a mesher and to a topology check).
    halves = [BRepBuilderAPI_MakeFace(gp_Cylinder(gp_Ax3(), 10.0), a, a + math.pi, 0.0, 20.0).Face()
              for a in (0.0, math.pi)]
    f = fused(client, *halves)
    assert len(f["faces"]) == 2
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[[0, 1]], merge=[[0, 1]])
    assert ok["valid"] is True and sorted(ok["faces"]) == [0, 1]
    shells = client.session.store.get(ok["handle"])
    # Free edges only at the two rims (each a half circle per half); both sides along the axis are shared.
    assert faces_per_edge(shells) == [1, 1, 1, 1, 2, 2]


def test_a_tube_in_bands_merges_its_bands_along_the_axis_but_never_all_the_way_round(client):
    # Two half tubes, each in two bands (a joint's strip below, the tube above, as a boss's wall grown down into
    # a floor): all four merged would close on themselves again; merged across the edges round the tube only,
    # each half is one face again, both sides along the axis shared between the halves.
    pieces = [BRepBuilderAPI_MakeFace(gp_Cylinder(gp_Ax3(), 10.0), a, a + math.pi, v0, v1).Face()
              for a in (0.0, math.pi) for v0, v1 in ((0.0, 1.5), (1.5, 20.0))]
    f = fused(client, *pieces)
    assert len(f["faces"]) == 4
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[[0, 1, 2, 3]], merge=[[0, 1, 2, 3]])
    shells_made = client.session.store.get(ok["handle"])
    assert ok["valid"] is True and len(ok["faces"]) == 2
    assert sorted(round(a, 6) for a in face_areas(shells_made)) == [round(10.0 * math.pi * 20.0, 6)] * 2
    # Free edges only at the two rims (a half circle per half and rim); both sides along the axis are shared
    # (each still in its two pieces: edges kept are not joined).
    assert faces_per_edge(shells_made) == [1, 1, 1, 1, 2, 2, 2, 2]


def test_a_whole_tube_merges_with_its_foot_half_by_half_across_a_joint_line_down_the_foot(client):
    # A boss's tube, whole round (z 3..20, written in two halves at its seam and halfway round), and its foot down
    # into a floor (z 0..3) in two pieces meeting at 0.5 and 0.5 + 3 radians, a rib's end standing on the first
    # line (a joint shared with another patch). The foot is cut at the tube's two lines too, and each half merges
    # with the foot beside it: the half from 0 with the foot from 0.5 on (the larger of the two pieces beside it,
    # which meet along the rib's line), the half from pi with all the foot beside it; the foot from 0 to 0.5
    # stays a face of its own. Before, a group holding a face split at its seam was left in pieces.
    cylinder = gp_Cylinder(gp_Ax3(), 10.0)
    tube = BRepBuilderAPI_MakeFace(cylinder, 0.0, 2.0 * math.pi, 3.0, 20.0).Face()
    foot = [BRepBuilderAPI_MakeFace(cylinder, a, b, 0.0, 3.0).Face() for a, b in ((0.5, 3.5), (3.5, 2 * math.pi + 0.5))]
    out = (math.cos(0.5), math.sin(0.5))
    rib = rectangle((10 * out[0], 10 * out[1], 0), (15 * out[0], 15 * out[1], 0), (15 * out[0], 15 * out[1], 3),
                    (10 * out[0], 10 * out[1], 3))
    f = fused(client, tube, *foot, rib)
    ids = {face["patch"]: [] for face in f["faces"]}
    for i, face in enumerate(f["faces"]):
        ids[face["patch"]].append(i)
    group = ids[0] + ids[1] + ids[2]
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[group + ids[3]], merge=[group])
    made = client.session.store.get(ok["handle"])
    assert ok["valid"] is True
    areas = sorted(round(a, 3) for a in face_areas(made))
    half, sliver = 10.0 * math.pi * 17.0, 10.0 * 0.5 * 3.0
    rib_area = 5.0 * 3.0
    assert areas == sorted(round(a, 3) for a in (sliver, rib_area, half + 10.0 * (math.pi - 0.5) * 3.0,
                                                 half + 10.0 * math.pi * 3.0))


@pytest.mark.parametrize("flange", [False, True])
def test_a_tube_sector_in_pieces_on_surfaces_seamed_apart_merges_into_one_face(client, flange):
    # A boss's mid-cylinder crossed by a rib off its axis: the sector on one side of the rib's mid-plane comes in
    # pieces, the arc offset from the skin (its surface's seam at angle 0 inside it) and the strips either side
    # down to the rib's mid-plane, each on a surface of its own (one with its axis the other way). Merged, they
    # are one face: laid on one surface whose seam runs outside them all (before, the arc stayed apart: the merge
    # gives up across a seam). With a flat flange running on from one side in the same set (a bend's plane), the
    # curved pieces still make one face, the flange another.
    def piece(a, b, flip=False):
        frame = gp_Ax3(gp_Pnt(0, 0, 0), gp.DZ_s(), gp.DX_s()).Rotated(gp.OZ_s(), a)
        if flip:
            frame = gp_Ax3(gp_Pnt(0, 0, 0), gp.DZ_s().Reversed(), gp.DX_s()).Rotated(gp.OZ_s(), a)
            return BRepBuilderAPI_MakeFace(gp_Cylinder(frame, 5.0), -(b - a), 0.0, -20.0, 0.0).Face()
        return BRepBuilderAPI_MakeFace(gp_Cylinder(frame, 5.0), 0.0, b - a, 0.0, 20.0).Face()

    arc = piece(-0.1, 3.0)
    strips = [piece(-0.5, -0.1, flip=True), piece(3.0, 3.4)]
    edge = (5.0 * math.cos(3.4), 5.0 * math.sin(3.4))
    along = (edge[0] - 10.0 * math.sin(3.4), edge[1] + 10.0 * math.cos(3.4))
    flat = [rectangle((*edge, 0), (*along, 0), (*along, 20), (*edge, 20))] if flange else []
    f = fused(client, arc, *strips, *flat)
    every = list(range(len(f["faces"])))
    assert len(every) == 3 + len(flat)
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[every], merge=[every])
    made = client.session.store.get(ok["handle"])
    assert ok["valid"] is True and len(ok["faces"]) == 1 + len(flat)
    areas = sorted(round(a, 6) for a in face_areas(made))
    assert areas == sorted([round(5.0 * 3.9 * 20.0, 6)] + [200.0] * len(flat))


class RecordingMerger:
    """Stands in for ShapeUpgrade_UnifySameDomain: records the shape it is given, then fails to build."""

    given = []

    def __init__(self, shape, *flags):
        RecordingMerger.given.append(shape)

    def SetLinearTolerance(self, value):
        pass

    def SetAngularTolerance(self, value):
        pass

    def KeepShapes(self, shapes):
        pass

    def Build(self):
        raise RuntimeError("Standard_Failure")


def test_the_merge_works_on_a_copy_so_a_merge_given_up_leaves_the_faces_as_they_were(monkeypatch):
    # UnifySameDomain edits the shape it is given in place (it re-fits pcurves on periodic surfaces): given the
    # shells' own faces, a merge it then gives up would still leave them changed, and written.
    RecordingMerger.given = []
    monkeypatch.setattr(shells, "ShapeUpgrade_UnifySameDomain", RecordingMerger)
    left = rectangle((0, 0, 1), (10, 0, 1), (10, 40, 1), (0, 40, 1))
    right = rectangle((10, 0, 1), (20, 0, 1), (20, 40, 1), (10, 40, 1))
    pieces = {0: [left], 1: [right]}
    shells._merge(pieces, [[0, 1]], 1e-6)
    (given,) = RecordingMerger.given
    assert pieces == {0: [left], 1: [right]}
    assert not any(f.IsSame(g) for f in (left, right) for g in indexed_map(given, TopAbs_FACE))


def test_the_faces_a_merge_hands_back_keep_their_orientation():
    # A reversed piece (a patch whose normal points the other way) stays reversed through the merge's copy.
    left = rectangle((0, 0, 1), (10, 0, 1), (10, 40, 1), (0, 40, 1))
    right = rectangle((10, 0, 1), (20, 0, 1), (20, 40, 1), (10, 40, 1))
    apart = rectangle((50, 0, 1), (60, 0, 1), (60, 40, 1), (50, 40, 1)).Reversed()
    pieces = {0: [left], 1: [right], 2: [apart]}
    shells._merge(pieces, [[0, 1]], 1e-6)
    assert len(pieces[2]) == 1 and pieces[2][0].Orientation() == apart.Orientation()


def test_a_wall_whose_foot_ends_inside_a_plate_stays_joined_once_written(client, tmp_path):
    # The wall's foot (x = 30, y 10..30) lies inside the plate, which holds it as an INTERNAL edge: a STEP file
    # drops that, and the wall would be joined to nothing. The plate is split along the foot carried on to its
    # boundary (x = 30, y 0..40), so the foot joins three faces.
    strip = rectangle((30, 10, 1), (30, 30, 1), (30, 30, 40), (30, 10, 40))
    f = fused(client, horizontal(), strip)
    plate = [i for i, face in enumerate(f["faces"]) if face["patch"] == 0]
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[list(range(len(f["faces"])))])
    assert ok["valid"] is True and ok["components"] == 1
    assert ok["faces"].count(plate[0]) == 2, "the plate is written as its two pieces"
    path = tmp_path / "foot.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    back = read_step(path)
    assert sorted(round(a) for a in face_areas(back)) == [780, 1200, 1200]
    assert edge_components(back) == 1
    assert faces_per_edge(back).count(3) == 1


def polygon_face(*corners):
    """A planar face bounded by the polygon through `corners`."""
    polygon = BRepBuilderAPI_MakePolygon()
    for corner in corners:
        polygon.Add(gp_Pnt(*corner))
    polygon.Close()
    return BRepBuilderAPI_MakeFace(polygon.Wire(), True).Face()


def test_a_floor_s_pieces_whose_merge_would_touch_its_hole_stay_pieces(client):
    # A floor round a boss's foot (the square hole) with a rib running into the boss along y = 0: the floor's
    # pieces below the rib and left of the piece beside it (`beside`) would merge into one face whose hole meets
    # its outer boundary at the rib's end (2, 0). Such a face passes BRepCheck, but a reader may rebuild it (see
    # the next test).
    below = polygon_face((-10, -10, 0), (10, -10, 0), (10, 0, 0), (2, 0, 0), (2, -2, 0), (-2, -2, 0), (-2, 0, 0),
                         (-10, 0, 0))
    left = polygon_face((-10, 0, 0), (-2, 0, 0), (-2, 2, 0), (2, 2, 0), (2, 0, 0), (6, 10, 0), (-10, 10, 0))
    beside = polygon_face((2, 0, 0), (10, 0, 0), (10, 10, 0), (6, 10, 0))
    rib = rectangle((2, 0, 0), (10, 0, 0), (10, 0, 5), (2, 0, 5))
    f = fused(client, below, left, beside, rib)
    floor = [i for i, face in enumerate(f["faces"]) if face["patch"] in (0, 1)]
    ok = client.ok("make_shells", handle=f["handle"], fuzzy=1e-6, shells=[list(range(len(f["faces"])))],
                   merge=[floor])
    made = client.session.store.get(ok["handle"])
    assert len(subshapes(made, TopAbs_FACE)) == len(f["faces"])
    assert not any(shells._wires_touch(face) for face in subshapes(made, TopAbs_FACE))
    assert faces_per_edge(made).count(3) == 1


def test_the_edges_shared_in_memory_stay_shared_in_the_file_where_a_rib_runs_into_a_boss(client, tmp_path):
    # The fused patches of the fixture rib_into_boss (see data/README.md) as the write stage gets them. Merged
    # whole, the floor's pieces made a face whose hole met its outer boundary where the rib ends at the boss; the
    # reader rebuilt that face, and its edge along the rib's foot came apart from the rib's: 57 mm of gap.
    shape = TopoDS_Shape()
    BRepTools.Read_s(shape, str(DATA / "rib_into_boss_fused.brep"), BRep_Builder())
    ok = client.ok("make_shells", handle=client.session.store.put(shape), fuzzy=3e-4,
                   shells=[[0, 1, 2, 5, 8, 9, 4, 7, 3, 6, 10, 13, 19, 11]],
                   merge=[[0, 1], [2, 5, 4, 3], [8, 9], [10, 19]])
    path = tmp_path / "rib_into_boss.step"
    client.ok("write_step", path=str(path), handle=ok["handle"], faces=[])
    made = client.session.store.get(ok["handle"])
    assert faces_per_edge(read_step(path)) == faces_per_edge(made)
