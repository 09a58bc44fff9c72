"""A straight line in a face's parameters is clipped to the face: the pieces between its boundary crossings that
lie inside, whatever the face's surface."""

import pytest
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_NurbsConvert
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
from OCP.BRep import BRep_Tool
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Ax2, gp_Dir, gp_Dir2d, gp_Pln, gp_Pnt, gp_Pnt2d

from midsurf_sidecar.geom.topology import boundary_length, subshapes
from midsurf_sidecar.geom.uv_lines import line_within


def plate_with_hole():
    """The plane z = 0 over x 0..10, y 0..5, less a hole of radius 1 at (5, 2.5)."""
    plate = BRepBuilderAPI_MakeFace(gp_Pln(), 0.0, 10.0, 0.0, 5.0).Face()
    pin = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5.0, 2.5, -1.0), gp_Dir(0, 0, 1)), 1.0, 2.0).Shape()
    return TopoDS.Face(subshapes(BRepAlgoAPI_Cut(plate, pin).Shape(), TopAbs_FACE)[0])


def lengths(pieces):
    return [round(boundary_length(p), 6) for p in pieces]


def test_a_line_across_a_hole_gives_the_pieces_on_either_side():
    pieces = line_within(plate_with_hole(), gp_Pnt2d(1.0, 2.5), gp_Dir2d(1.0, 0.0), 20.0)
    assert lengths(pieces) == [3.0, 4.0]


def test_a_line_leaving_the_face_stops_at_its_boundary():
    pieces = line_within(plate_with_hole(), gp_Pnt2d(2.0, 1.0), gp_Dir2d(0.0, -1.0), 20.0)
    assert lengths(pieces) == [1.0]


def test_a_line_along_the_boundary_cuts_nothing():
    assert line_within(plate_with_hole(), gp_Pnt2d(-1.0, 0.0), gp_Dir2d(1.0, 0.0), 20.0) == []


@pytest.mark.parametrize("start", [(0.2, 4.9), (9.9, 0.05)])
def test_a_line_on_a_bspline_face_is_clipped_as_on_its_plane(start):
    # The same plate as a B-spline surface: its parameters are the plane's, so the pieces are the same.
    face = TopoDS.Face(BRepBuilderAPI_NurbsConvert(plate_with_hole(), True).Shape())
    assert BRep_Tool.Surface_s(face).DynamicType().Name() == "Geom_BSplineSurface"
    planar = line_within(plate_with_hole(), gp_Pnt2d(*start), gp_Dir2d(1.0, -1.0), 20.0)
    curved = line_within(face, gp_Pnt2d(*start), gp_Dir2d(1.0, -1.0), 20.0)
    assert lengths(planar) and lengths(curved) == pytest.approx(lengths(planar), abs=1e-6)
