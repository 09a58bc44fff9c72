"""The shared boolean calls: a split that does not keep its faces' area is refused; merging a patch's faces
leaves the faces it was given as they were."""

import math

import pytest
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_NurbsConvert
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.Geom import Geom_OffsetSurface
from OCP.gp import gp_Ax3, gp_Cylinder, gp_Dir, gp_Pln, gp_Pnt
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_FACE, TopAbs_WIRE
from OCP.TopoDS import TopoDS

from midsurf_sidecar.geom import booleans
from midsurf_sidecar.geom.booleans import arguments, check_area_kept, general_fuse, unify
from midsurf_sidecar.geom.pole_offset import on_pole_offset
from midsurf_sidecar.geom.topology import subshapes, surface_props
from midsurf_sidecar.protocol.errors import KernelError
from patch_shapes import horizontal, rectangle, vertical


class Pieces:
    """What BOPAlgo's history answers for one face: its images."""

    def __init__(self, faces):
        self.faces = faces

    def Size(self):
        return len(self.faces)

    def __iter__(self):
        return iter(self.faces)


class History:
    """A builder whose result replaced `face` by `pieces` and kept every other face."""

    def __init__(self, face, pieces):
        self.face, self.pieces = face, pieces

    def Modified(self, face):
        return Pieces(self.pieces if face.IsSame(self.face) else [])

    def IsDeleted(self, face):
        return False


def test_a_real_split_keeps_the_area():
    # The L of two plates crossing: each is cut in two, and the pieces cover it.
    faces = [horizontal(), vertical(30)]
    builder = general_fuse(faces, 1e-6)
    assert all(builder.Modified(face).Size() == 2 for face in faces)
    check_area_kept(builder, faces, 1e-6)


def test_a_face_whose_pieces_lost_half_of_it_is_a_broken_split():
    plate = horizontal()  # 60 x 40
    half = rectangle((0, 0, 1), (30, 0, 1), (30, 40, 1), (0, 40, 1))
    with pytest.raises(KernelError, match="lost 1200.000 of 2400.000"):
        check_area_kept(History(plate, [half]), [plate], 1e-6)


def test_what_the_fuzzy_value_moves_is_no_loss():
    # A piece 0.001 short of the face along its 40 long side: within fuzzy 0.001 x its 200 boundary.
    plate = horizontal()
    short = rectangle((0, 0, 1), (59.999, 0, 1), (59.999, 40, 1), (0, 40, 1))
    check_area_kept(History(plate, [short]), [plate], 1e-3)


def test_the_fuse_runs_on_one_thread_when_asked(monkeypatch):
    # midsurf runs a part again with MIDSURF_SERIAL_BOOLEANS=1 after OCCT crashed in it: the same split, serial.
    faces = [horizontal(), vertical(30)]
    monkeypatch.delenv("MIDSURF_SERIAL_BOOLEANS", raising=False)
    assert general_fuse(faces, 1e-6).RunParallel()
    monkeypatch.setenv("MIDSURF_SERIAL_BOOLEANS", "1")
    serial = general_fuse(faces, 1e-6)
    assert not serial.RunParallel()
    assert all(serial.Modified(face).Size() == 2 for face in faces)


def test_a_split_runs_on_threads_unless_asked_for_one_with_the_same_pieces(monkeypatch):
    # A split of a large output's faces by their seams took 21 s on one thread and 12 s on two, same pieces.
    plate, wall = horizontal(), vertical(30)
    monkeypatch.delenv("MIDSURF_SERIAL_BOOLEANS", raising=False)
    threaded = booleans.split(plate, [wall], 1e-6)
    assert threaded.RunParallel()
    monkeypatch.setenv("MIDSURF_SERIAL_BOOLEANS", "1")
    serial = booleans.split(plate, [wall], 1e-6)
    assert not serial.RunParallel()
    areas = [[round(surface_props(f).Mass(), 9) for f in s.Modified(plate)] for s in (threaded, serial)]
    assert len(areas[0]) == 2 and areas[0] == areas[1]


def offset_faces(shape):
    """Each face of `shape` as a B-spline, offset by 1 mm (Geom_OffsetSurface), as a mid-patch of a freeform wall."""
    faces = []
    for face in subshapes(BRepBuilderAPI_NurbsConvert(shape, True).Shape(), TopAbs_FACE):
        surface = BRep_Tool.Surface_s(TopoDS.Face(face))
        faces.append(BRepBuilderAPI_MakeFace(Geom_OffsetSurface(surface, 1.0), 1e-7).Face())
    return faces


def test_a_fuse_of_an_offset_freeform_surface_with_a_pole_runs_on_one_thread(monkeypatch):
    # OCCT's evaluation of such an offset near its pole is not thread-safe (a core dump had two threads in
    # Geom_OsculatingSurface); offsets of freeform surfaces without a pole keep both threads.
    monkeypatch.delenv("MIDSURF_SERIAL_BOOLEANS", raising=False)
    dome = offset_faces(BRepPrimAPI_MakeSphere(10.0).Shape())
    flat = offset_faces(BRepPrimAPI_MakeBox(20.0, 20.0, 20.0).Shape())
    assert [on_pole_offset(f) for f in dome] == [True]
    assert not any(on_pole_offset(f) for f in flat)
    assert not on_pole_offset(BRepBuilderAPI_NurbsConvert(BRepPrimAPI_MakeSphere(10.0).Shape(), True).Shape())
    plate = horizontal()  # z = 1: it crosses the dome (radius 11 about the origin)
    assert not general_fuse(dome + [plate], 1e-6).RunParallel()
    assert general_fuse(flat[:1] + [plate], 1e-6).RunParallel()


class Merger:
    """Stands in for ShapeUpgrade_UnifySameDomain: keeps the shape it is given, answers `result` (or that shape)."""

    given = []

    def __init__(self, shape, *flags, result=None):
        Merger.given.append(shape)
        self.result = result if result is not None else shape

    def SetLinearTolerance(self, value):
        pass

    def SetAngularTolerance(self, value):
        pass

    def Build(self):
        pass

    def Shape(self):
        return self.result


def test_merging_works_on_a_copy_so_the_faces_given_are_never_changed(monkeypatch):
    # UnifySameDomain edits the shape it is given in place (it re-fits pcurves of edges on periodic surfaces).
    # A face the fuse leaves whole is the very face of the stitched patches: edited, it broke every later fuse.
    Merger.given = []
    monkeypatch.setattr(booleans, "ShapeUpgrade_UnifySameDomain", Merger)
    apart = rectangle((100, 0, 0), (110, 0, 0), (110, 10, 0), (100, 10, 0))  # touches nothing: not split
    faces = [horizontal(), apart]
    unify(faces, 1e-6)
    (given,) = Merger.given
    assert not any(f.IsSame(g) for f in faces for g in subshapes(given, TopAbs_FACE))


def test_a_merge_that_breaks_a_face_is_dropped_for_the_faces_only_joined(monkeypatch):
    # Its wire turned inside out: the merged face's area reads negative.
    plate = horizontal()
    inverted = plate.EmptyCopied()
    BRep_Builder().Add(inverted, subshapes(plate, TopAbs_WIRE)[0].Reversed())
    assert surface_props(inverted).Mass() < 0
    monkeypatch.setattr(booleans, "ShapeUpgrade_UnifySameDomain", lambda shape, *flags: Merger(shape, result=inverted))
    faces = [horizontal(), vertical(30)]
    joined = subshapes(unify(faces, 1e-6), TopAbs_FACE)
    assert len(joined) == 4 and all(surface_props(f).Mass() > 0 for f in joined)


@pytest.mark.parametrize("gap", [0.0, 0.2])
def test_pieces_that_would_merge_into_a_ring_are_only_joined(gap):
    # A tube's arc (three quarters round) and the band that closes its gap (the last quarter, less `gap`): merged,
    # they would be one face all the way round its cylinder, which the next fuse broke; they stay two faces,
    # joined along their shared line. With a gap left between them, they merge into one face.
    cylinder = gp_Cylinder(gp_Ax3(), 10.0)
    arc = BRepBuilderAPI_MakeFace(cylinder, 0.0, 1.5 * math.pi, 0.0, 5.0).Face()
    band = BRepBuilderAPI_MakeFace(cylinder, 1.5 * math.pi, 2.0 * math.pi - gap, 0.0, 5.0).Face()
    faces = subshapes(unify([arc, band], 1e-6), TopAbs_FACE)
    assert len(faces) == (2 if gap == 0.0 else 1)
    area = sum(surface_props(f).Mass() for f in faces)
    assert area == pytest.approx(10.0 * (2.0 * math.pi - gap) * 5.0)


def test_a_whole_tube_and_its_foot_still_merge_into_one_ring():
    # A tube that was whole before (its mid-cylinder all the way round) and the foot grown from its edge.
    cylinder = gp_Cylinder(gp_Ax3(), 10.0)
    tube = BRepBuilderAPI_MakeFace(cylinder, 0.0, 2.0 * math.pi, 2.0, 5.0).Face()
    foot = BRepBuilderAPI_MakeFace(cylinder, 0.0, 2.0 * math.pi, 0.0, 2.0).Face()
    faces = subshapes(unify([tube, foot], 1e-6), TopAbs_FACE)
    assert len(faces) == 1
    assert surface_props(faces[0]).Mass() == pytest.approx(10.0 * 2.0 * math.pi * 5.0)


def test_fuse_arguments_are_a_face_alone_a_compound_for_a_group_and_loose_faces_below_two():
    a, b, c = (BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), 0, 1, 0, 1).Face() for z in (0, 1, 2))
    alone, group = arguments([[a], [b, c], []])
    assert alone.IsSame(a)
    assert group.ShapeType() == TopAbs_COMPOUND and len(subshapes(group, TopAbs_FACE)) == 2
    loose = arguments([[a, b, c]])
    assert len(loose) == 3 and all(x.IsSame(y) for x, y in zip(loose, (a, b, c)))


def test_a_faces_area_is_integrated_once_and_told_apart_from_another_face_and_orientation(monkeypatch):
    from midsurf_sidecar.geom import topology

    calls = []
    integrate = topology.surface_props
    monkeypatch.setattr(topology, "surface_props", lambda shape: calls.append(shape) or integrate(shape))
    monkeypatch.setattr(topology, "_FACE_PROPS", {})
    plate, other = horizontal(), vertical(30.0)
    first = topology.face_props(plate)
    assert topology.face_props(plate) is first and len(calls) == 1
    assert first.Mass() == pytest.approx(integrate(plate).Mass(), rel=1e-12)
    assert topology.face_props(other).Mass() == pytest.approx(integrate(other).Mass(), rel=1e-12)
    assert topology.face_props(plate.Reversed()) is not first and len(calls) == 3
    # Past FACE_PROPS_KEPT faces, all are dropped: the next face is integrated again.
    monkeypatch.setattr(topology, "FACE_PROPS_KEPT", 1)
    topology.face_props(vertical(45.0))
    topology.face_props(plate)
    assert len(calls) == 5
