"""A freeform dome's mid-patch: an offset of a B-spline surface with a pole, made as its B-spline approximation."""

import math

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakeOffsetShape
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.Geom import Geom_BSplineSurface
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS

from midsurf_sidecar.geom.pole_offset import as_bspline, on_pole_offset
from midsurf_sidecar.geom.topology import subshapes, surface_props
from midsurf_sidecar.patch.face_offset import offset_face


def nurbs_faces(shape):
    return [TopoDS.Face(f) for f in subshapes(BRepBuilderAPI_NurbsConvert(shape, True).Shape(), TopAbs_FACE)]


def raw_offset(face, distance):
    """What OCCT's offset gives, before midsurf approximates it."""
    maker = BRepOffsetAPI_MakeOffsetShape()
    maker.PerformBySimple(face, distance)
    return maker.Shape()


def read_back_faces(face, path):
    writer = STEPControl_Writer()
    writer.Transfer(face, STEPControl_AsIs)
    writer.Write(str(path))
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    return subshapes(reader.OneShape(), TopAbs_FACE)


def test_a_dome_offset_is_made_as_a_b_spline_a_step_file_keeps(tmp_path):
    # A sphere R 10 as a B-spline (its poles collapse at both ends), offset 1 inwards: the mid-patch of a dome
    # 2 thick. As an offset surface the STEP reader drops it; as its approximation it reads back whole, valid,
    # with the area of the sphere R 9.
    (sphere,) = nurbs_faces(BRepPrimAPI_MakeSphere(10.0).Shape())
    raw = TopoDS.Face(subshapes(raw_offset(sphere, -1.0), TopAbs_FACE)[0])
    assert on_pole_offset(raw)
    assert read_back_faces(raw, tmp_path / "raw.step") == []
    patch = offset_face(sphere, -1.0)
    assert isinstance(BRep_Tool.Surface_s(patch), Geom_BSplineSurface) and not on_pole_offset(patch)
    assert BRepCheck_Analyzer(patch).IsValid()
    assert surface_props(patch).Mass() == pytest.approx(4 * math.pi * 81, rel=1e-4)
    (back,) = read_back_faces(patch, tmp_path / "patch.step")
    assert BRepCheck_Analyzer(back).IsValid()


def test_an_offset_of_a_freeform_surface_without_a_pole_stays_an_offset():
    face = nurbs_faces(BRepPrimAPI_MakeBox(20.0, 20.0, 20.0).Shape())[0]
    patch = offset_face(face, -1.0)
    assert not on_pole_offset(patch)
    assert as_bspline(patch).IsSame(patch)
