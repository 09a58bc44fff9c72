"""The shared boolean calls: a split that does not keep its faces' area is refused."""

import pytest

from midsurf_sidecar.geom.booleans import check_area_kept, general_fuse
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
