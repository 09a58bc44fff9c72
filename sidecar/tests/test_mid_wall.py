"""A tapered wall's face moved to mid-wall point by point: each point half-way to the partner along its normal,
the face's own boundary kept; faces whose B-spline form has other parameters are offset at the mean."""

import math

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepTools import BRepTools
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon, BRepBuilderAPI_NurbsConvert
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakePrism
from OCP.GProp import GProp_GProps
from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cylinder
from OCP.TopAbs import TopAbs_FACE, TopAbs_VERTEX
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Vec

from midsurf_sidecar.geom.face_point import area_samples
from midsurf_sidecar.geom.topology import diagonal, subshapes
from midsurf_sidecar.patch.mid_wall import mid_wall_face


def wedge():
    """A plate over x 0..60, y 0..40 whose thickness grows from 1 at x = 0 to 3 at x = 60: bottom z = 0, top
    z = 1 + x / 30. Its faces, found by their centroids: (bottom, top)."""
    outline = BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 0), gp_Pnt(60, 0, 0), gp_Pnt(60, 0, 3), gp_Pnt(0, 0, 1), True)
    section = BRepBuilderAPI_MakeFace(outline.Wire()).Face()
    solid = BRepPrimAPI_MakePrism(section, gp_Vec(0, 40, 0)).Shape()
    faces = subshapes(solid, TopAbs_FACE)

    def centroid(face):
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(face, props)
        return props.CentreOfMass()

    bottom = next(f for f in faces if abs(centroid(f).Z()) < 1e-9)
    top = next(f for f in faces if centroid(f).Z() > 1.5 and 0 < centroid(f).X() < 60 and 0 < centroid(f).Y() < 40)
    return TopoDS.Face(bottom), TopoDS.Face(top)


def heights(face):
    """(x, z) of area samples of `face`."""
    adaptor = BRepAdaptor_Surface(face, True)
    points = (adaptor.Value(u, v) for _, u, v in area_samples(face, diagonal(face), 5.0))
    return [(p.X(), p.Z()) for p in points]


@pytest.mark.parametrize("as_bspline", [False, True])
def test_a_wedge_face_goes_half_way_to_its_partner_everywhere(as_bspline):
    bottom, top = wedge()
    if as_bspline:
        bottom = TopoDS.Face(subshapes(BRepBuilderAPI_NurbsConvert(bottom, True).Shape(), TopAbs_FACE)[0])
    moved = mid_wall_face(bottom, [top], -1.0)
    assert BRepCheck_Analyzer(moved).IsValid()
    assert BRepAdaptor_Surface(moved, True).GetType() == GeomAbs_BSplineSurface
    samples = heights(moved)
    assert len(samples) > 20
    # Mid-wall of the wedge: z = (1 + x / 30) / 2, where an offset at the mean thickness would be off by 0.5.
    assert max(abs(z - (1 + x / 30) / 2) for x, z in samples) < 1e-6
    # The boundary is the face's own, moved: the same x and y extent.
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(moved, props)
    assert props.Mass() == pytest.approx(60 * 40 * (1 + (1 / 60) ** 2) ** 0.5, rel=1e-6)
    assert moved.Orientation() == bottom.Orientation()


def kind(face):
    return BRepAdaptor_Surface(face).GetType()


def test_a_cylinder_is_offset_at_the_mean():
    cylinder = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 10.0, 5.0).Shape()
    side = next(f for f in map(TopoDS.Face, subshapes(cylinder, TopAbs_FACE)) if kind(f) == GeomAbs_Cylinder)
    inner = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 8.0, 5.0).Shape()
    partner = next(f for f in map(TopoDS.Face, subshapes(inner, TopAbs_FACE)) if kind(f) == GeomAbs_Cylinder)
    moved = mid_wall_face(side, [partner], -1.0)
    assert BRepAdaptor_Surface(moved, True).Cylinder().Radius() == pytest.approx(9.0)


def quarter(centre, radius, base=0.0):
    """The curved face of a quarter cylinder 5 high on a vertical axis through `centre` from z = `base`, from
    angle 0 to 90."""
    axis = gp_Ax2(gp_Pnt(*centre, base), gp_Dir(0, 0, 1))
    solid = BRepPrimAPI_MakeCylinder(axis, radius, 5.0, math.pi / 2).Shape()
    return next(f for f in map(TopoDS.Face, subshapes(solid, TopAbs_FACE)) if kind(f) == GeomAbs_Cylinder)


def test_a_bend_drawn_on_centres_apart_goes_onto_the_mean_cylinder():
    # A bend's outer arc R 5 about (0, 0) and inner arc R 3.6 about (0.1, 0.1): the flats beside it are 1.5 thick
    # at angle 0 (x from 3.7 to 5) and at 90 degrees alike, the bend thicker in between. The mean cylinder, R 4.3
    # about (0.05, 0.05), meets each flat's mid-plane (x = 4.35 at angle 0, y = 4.35 at 90) tangentially, at the
    # angles the outer face spans; an offset of the outer arc at the mean thickness would stand off both.
    moved = mid_wall_face(quarter((0, 0), 5.0), [quarter((0.1, 0.1), 3.6)], -0.76)
    assert BRepCheck_Analyzer(moved).IsValid()
    cylinder = BRepAdaptor_Surface(moved, True).Cylinder()
    assert cylinder.Radius() == pytest.approx(4.3)
    assert (cylinder.Location().X(), cylinder.Location().Y()) == pytest.approx((0.05, 0.05))
    ends = [BRep_Tool.Pnt_s(TopoDS.Vertex(v)) for v in subshapes(moved, TopAbs_VERTEX)]
    ends = [p for p in ends if abs(p.Z()) < 1e-9]
    assert sorted({(round(p.X(), 9), round(p.Y(), 9)) for p in ends}) == [(0.05, 4.35), (4.35, 0.05)]


def test_the_mean_cylinder_ends_half_way_between_its_skins_ends_along_the_axis():
    # A tub's vertical corner drawn on axes apart: the outer skin from z = 0, the inner from z = -0.1 (its
    # bottom corner's centre lies 0.1 lower too). The mean cylinder runs from z = -0.05 to 4.95, where the mean
    # sphere below and the rim's mid-line meet it; kept at the outer skin's range it stood 0.05 off the sphere.
    moved = mid_wall_face(quarter((0, 0), 5.0), [quarter((0.1, 0.1), 3.6, base=-0.1)], -0.76)
    assert BRepCheck_Analyzer(moved).IsValid()
    heights = {round(BRep_Tool.Pnt_s(TopoDS.Vertex(v)).Z(), 9) for v in subshapes(moved, TopAbs_VERTEX)}
    assert heights == {-0.05, 4.95}


def test_the_moved_plane_runs_on_past_the_face_at_mid_wall():
    # Room for the joints: the surface under the moved face reaches past its boundary (2 mean walls, here 4 mm),
    # still half-way between the skins' planes there.
    bottom, top = wedge()
    moved = mid_wall_face(bottom, [top], -1.0)
    surface = BRep_Tool.Surface_s(moved)
    u0, u1, v0, v1 = surface.Bounds()
    fu0, fu1, fv0, fv1 = BRepTools.UVBounds_s(moved)
    assert u0 < fu0 - 3.9 and u1 > fu1 + 3.9 and v0 < fv0 - 3.9 and v1 > fv1 + 3.9
    for u, v in ((u0, v0), (u1, v1), (u0, v1)):
        p = surface.Value(u, v)
        assert p.Z() == pytest.approx((1 + p.X() / 30) / 2, abs=1e-6)
