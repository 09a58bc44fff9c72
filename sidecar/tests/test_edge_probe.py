"""TargetFaces: rays meet a strip swept along a line from a spline where its exact support surface says."""

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.Geom import Geom_BSplineSurface, Geom_Line, Geom_SurfaceOfLinearExtrusion
from OCP.GeomAPI import GeomAPI_IntCS
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Dir, gp_Lin, gp_Pnt, gp_Vec

from midsurf_sidecar.joints.edge_probe import TargetFaces


def swept_spline_strip():
    """A wavy spline in z = 0 (x from 0 to 40) swept 10 mm up: a face on a surface of linear extrusion."""
    from build123d import Edge

    edge = Edge.make_spline([(0, 0, 0), (10, 3, 0), (20, 0, 0), (30, -3, 0), (40, 0, 0)]).wrapped
    strip = BRepPrimAPI_MakePrism(edge, gp_Vec(0, 0, 10)).Shape()
    explorer = TopExp_Explorer(strip, TopAbs_FACE)
    return TopoDS.Face(explorer.Current())


def test_a_ray_meets_a_swept_spline_strip_as_its_extrusion_surface_says():
    face = swept_spline_strip()
    surface = BRep_Tool.Surface_s(face)
    assert isinstance(surface, Geom_SurfaceOfLinearExtrusion)
    targets = TargetFaces({0: face}, reach=30.0)
    assert isinstance(targets.surfaces[0], Geom_BSplineSurface)
    for x, z in [(5, 1), (20, 5), (35, 9.5), (12, 12)]:
        origin, direction = (x, -20.0, z), (0.0, 1.0, 0.0)
        hits = targets.hits(origin, direction, 30.0, [0])
        exact = GeomAPI_IntCS(Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction))), surface)
        expected = sorted(exact.Point(k).Y() + 20.0 for k in range(1, exact.NbPoints() + 1))
        assert [h["distance"] for h in hits] == pytest.approx(expected, abs=1e-7)
        # Beyond the strip's top (z = 12) the meeting is on the support surface, 2 mm from the face.
        assert hits[0]["gap"] == pytest.approx(max(0.0, z - 10.0), abs=1e-6)
