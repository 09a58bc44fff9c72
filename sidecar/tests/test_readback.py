"""The read-back check names the written faces a reader breaks or drops."""

from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Compound, TopoDS_Shell

from midsurf_sidecar.geom.topology import indexed_map
from midsurf_sidecar.write import readback
from shapes import box, shaft


def shells_of(groups):
    """A compound of shells, one per list of faces."""
    builder = BRep_Builder()
    compound = TopoDS_Compound()
    builder.MakeCompound(compound)
    for faces in groups:
        shell = TopoDS_Shell()
        builder.MakeShell(shell)
        for face in faces:
            builder.Add(shell, face)
        builder.Add(compound, shell)
    return compound


def written_and_checked(shape, path):
    """`shape` written to `path` as STEP (plain writer) and the read-back check of it."""
    writer = STEPControl_Writer()
    writer.Transfer(shape, STEPControl_AsIs)
    writer.Write(str(path))
    return readback.check_written(str(path), shape)


def box_faces():
    faces = indexed_map(box(), TopAbs_FACE)
    return [faces.FindKey(i + 1) for i in range(faces.Size())]


def test_a_shell_read_back_empty_names_its_faces():
    faces = box_faces()
    written = shells_of([faces[:2], faces[2:5], faces[5:]])
    back = shells_of([faces[:2], [], faces[5:]])
    own = indexed_map(written, TopAbs_FACE)
    assert readback._lost_faces(back, written, own) == {2, 3, 4}


def test_shells_read_back_split_name_nothing():
    # The reader split a shell: positions no longer match, so no face can be named by its shell.
    faces = box_faces()
    written = shells_of([faces[:3], faces[3:]])
    back = shells_of([faces[:1], faces[1:3], [], faces[3:]])
    assert readback._lost_faces(back, written, indexed_map(written, TopAbs_FACE)) == set()


def test_a_face_read_back_comes_from_the_face_its_edges_lie_on():
    faces = box_faces()
    boxes = [readback._box(face) for face in faces]
    for k, face in enumerate(faces):
        assert readback._origin(face, faces, boxes, 1e-3) == k


def test_a_face_without_a_wire_is_named_broken(tmp_path):
    # A face without a wire stands for its whole unbounded surface: broken even where BRepCheck passes it.
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Pln
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    faces = box_faces()
    infinite = BRepBuilderAPI_MakeFace(gp_Pln()).Face()
    written = shells_of([faces[:3], [infinite], faces[3:]])
    path = str(tmp_path / "unbounded.step")
    writer = STEPControl_Writer()
    writer.Transfer(written, STEPControl_AsIs)
    writer.Write(path)
    own = indexed_map(written, TopAbs_FACE)
    check = readback.check_written(path, written)
    assert not check.valid
    assert check.invalid == [own.FindIndex(infinite) - 1]
    bounded = shells_of([faces])
    writer = STEPControl_Writer()
    writer.Transfer(bounded, STEPControl_AsIs)
    writer.Write(str(tmp_path / "box.step"))
    assert readback.check_written(str(tmp_path / "box.step"), bounded).valid


def test_the_check_reports_how_far_edges_read_back_lie_off_their_faces(tmp_path):
    # A face on the plane z = 0 whose wire has a corner 0.2 above it: its edges stray up to 0.2 from the face,
    # which the reader's tolerances keep; a box's edges lie on their faces.
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.gp import gp_Pln, gp_Pnt

    def written(shape, name):
        return written_and_checked(shape, tmp_path / name)

    polygon = BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 10, 0.2), gp_Pnt(0, 10, 0), True)
    loose = BRepBuilderAPI_MakeFace(gp_Pln(), polygon.Wire()).Face()
    assert 0.1 < written(shells_of([[loose]]), "loose.step").max_edge_tolerance < 0.3
    assert written(shells_of([box_faces()]), "box.step").max_edge_tolerance < 1e-5


def test_the_check_counts_the_free_edges_read_back(tmp_path):
    # A box's six faces in one shell share every edge; in a shell each, every edge is free on each face (24).
    faces = box_faces()
    assert written_and_checked(shells_of([faces]), tmp_path / "closed.step").free_edges == 0
    apart = [[BRepBuilderAPI_Copy(face).Shape()] for face in faces]
    assert written_and_checked(shells_of(apart), tmp_path / "apart.step").free_edges == 24
    # A cylinder's seam joins its face to itself: no free edge (a solid kept as it is, `--keep-solids`).
    assert written_and_checked(shaft(), tmp_path / "shaft.step").free_edges == 0


def test_an_empty_face_written_is_named_broken_not_a_crash(tmp_path):
    # A face with neither surface nor wire has a void bounding box, whose corners OCCT refuses to give: the
    # check names the face instead of failing the write.
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    from OCP.TopoDS import TopoDS_Face

    faces = box_faces()
    empty = TopoDS_Face()
    BRep_Builder().MakeFace(empty)
    assert readback._box(empty) is None
    written = shells_of([faces, [empty]])
    path = str(tmp_path / "empty.step")
    writer = STEPControl_Writer()
    writer.Transfer(written, STEPControl_AsIs)
    writer.Write(path)
    check = readback.check_written(path, written)
    assert not check.valid
    assert indexed_map(written, TopAbs_FACE).FindIndex(empty) - 1 in check.invalid


def test_a_broken_face_read_back_in_another_order_names_the_face_it_lies_on(monkeypatch):
    # As many faces read as written, but in another order (a reader may take shells apart and put them back
    # otherwise): the broken face is named by the written face it lies on, not by its place in the file.
    from OCP.IFSelect import IFSelect_RetDone

    faces = box_faces()
    written = shells_of([faces[:3], faces[3:]])
    back = shells_of([faces[3:], faces[:3]])
    broken = faces[4]

    class Reader:
        def ReadFile(self, path):
            return IFSelect_RetDone

        def TransferRoots(self):
            pass

        def OneShape(self):
            return back

    class Check:
        def __init__(self, shape):
            self.shape = shape

        def IsValid(self):
            return not (self.shape.IsSame(back) or self.shape.IsSame(broken))

    monkeypatch.setattr(readback, "STEPControl_Reader", Reader)
    monkeypatch.setattr(readback, "BRepCheck_Analyzer", Check)
    check = readback.check_written("unused.step", written)
    assert not check.valid
    assert check.invalid == [indexed_map(written, TopAbs_FACE).FindIndex(broken) - 1]
