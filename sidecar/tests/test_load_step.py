"""load_step: solids as handles, and a clear error code for every way a file can be wrong."""

import pytest
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder
from OCP.BRepBndLib import BRepBndLib
from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf, gp_Vec
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Compound

from midsurf_sidecar.load.step_reader import load_step

from shapes import box, write_step


def test_box(client, tmp_path):
    solids = client.ok("load_step", path=str(write_step(box(10, 20, 30), tmp_path / "box.step")))["solids"]
    assert len(solids) == 1
    solid = solids[0]
    assert solid["handle"] >= 1
    assert solid["faces"] == 6
    assert solid["volume"] == pytest.approx(6000.0)
    assert solid["area"] == pytest.approx(2 * (200 + 300 + 600))


def test_real_part_e_plate(client, e_plate_path):
    solids = client.ok("load_step", path=str(e_plate_path))["solids"]
    assert len(solids) == 1
    assert solids[0]["faces"] == 56
    assert solids[0]["volume"] == pytest.approx(9859.45, rel=1e-3)


def test_several_solids_in_topexp_order(client, tmp_path):
    compound = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(compound)
    builder.Add(compound, box(1, 1, 1))
    builder.Add(compound, box(2, 2, 2))
    solids = client.ok("load_step", path=str(write_step(compound, tmp_path / "two.step")))["solids"]
    assert [s["volume"] for s in solids] == pytest.approx([1.0, 8.0])
    assert len({s["handle"] for s in solids}) == 2


def test_solids_placed_by_a_location_come_with_their_placement_in_their_geometry(client, tmp_path):
    # An assembly places one part twice, as one shape under two locations (rotated and moved): each solid loaded
    # has no location left, and its geometry lies where the file placed it.
    placed = []
    for angle, dx in [(0.7, 0.0), (1.9, 40.0)]:
        move = gp_Trsf()
        move.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 1, 0)), angle)
        shift = gp_Trsf()
        shift.SetTranslation(gp_Vec(dx, 5, 7))
        placed.append(box(10, 20, 30).Located(TopLoc_Location(shift * move)))
    compound = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(compound)
    for solid in placed:
        builder.Add(compound, solid)
    path = write_step(compound, tmp_path / "instances.step")
    loaded = load_step(str(path))
    assert len(loaded) == 2
    for got, want in zip(loaded, placed):
        assert got.Location().IsIdentity()
        assert bounds(got) == pytest.approx(bounds(want), abs=1e-6)


def bounds(shape):
    box_ = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box_, False, False)
    return [box_.CornerMin().X(), box_.CornerMin().Y(), box_.CornerMin().Z(),
            box_.CornerMax().X(), box_.CornerMax().Y(), box_.CornerMax().Z()]


def test_missing_file(client, tmp_path):
    err = client.err("load_step", path=str(tmp_path / "nope.step"))
    assert err["code"] == "not_found"
    assert err["message"] == "no such file"


def test_directory(client, tmp_path):
    err = client.err("load_step", path=str(tmp_path))
    assert err["code"] == "not_a_file"
    assert "directory" in err["message"]


def test_empty_file(client, tmp_path):
    path = tmp_path / "empty.step"
    path.write_bytes(b"")
    err = client.err("load_step", path=str(path))
    assert err["code"] == "read_failed"
    assert "empty" in err["message"]
    assert "IFSelect_Ret" in err["message"]


def test_not_step(client, tmp_path):
    path = tmp_path / "notes.step"
    path.write_text("these are not the droids you are looking for\n")
    err = client.err("load_step", path=str(path))
    assert err["code"] == "read_failed"
    assert "IFSelect_Ret" in err["message"]


def test_truncated_real_file(client, tmp_path, e_plate_path):
    data = e_plate_path.read_bytes()
    path = tmp_path / "half.step"
    path.write_bytes(data[: len(data) // 2])
    assert client.err("load_step", path=str(path))["code"] in ("read_failed", "no_solid")
    # The session survives and still works.
    assert client.ok("load_step", path=str(e_plate_path))["solids"][0]["faces"] == 56


def test_faces_but_no_solid(client, tmp_path):
    face = TopExp_Explorer(box(), TopAbs_FACE).Current()
    err = client.err("load_step", path=str(write_step(face, tmp_path / "face.step")))
    assert err["code"] == "no_solid"
    # The STEP writer wraps a lone face in an open shell.
    assert "1 face" in err["message"] and "open shell" in err["message"] and "no solid" in err["message"]


def test_path_must_be_a_string(client):
    assert client.err("load_step", path=3)["code"] == "bad_args"
    assert client.err("load_step")["code"] == "bad_args"
