"""TargetFaces: rays meet a strip swept along a line from a spline where its exact support surface says."""

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.Geom import Geom_BSplineSurface, Geom_Line, Geom_OffsetSurface, Geom_SurfaceOfLinearExtrusion
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
    assert isinstance(targets.surfaces[0].exact, Geom_BSplineSurface)
    for x, z in [(5, 1), (20, 5), (35, 9.5), (12, 12)]:
        origin, direction = (x, -20.0, z), (0.0, 1.0, 0.0)
        hits = targets.hits(origin, direction, 30.0, [0])
        exact = GeomAPI_IntCS(Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction))), surface)
        expected = sorted(exact.Point(k).Y() + 20.0 for k in range(1, exact.NbPoints() + 1))
        assert [h["distance"] for h in hits] == pytest.approx(expected, abs=1e-7)
        # Beyond the strip's top (z = 12) the meeting is on the support surface, 2 mm from the face.
        assert hits[0]["gap"] == pytest.approx(max(0.0, z - 10.0), abs=1e-6)


def offset_spline_face(wavy=False):
    """A doubly curved bicubic spline sheet (60 x 40, bulging 6 mm) offset by 1.5 mm: a freeform mid-patch.
    `wavy`: rippled too (1 mm, 4 waves along x), so that its approximation takes several spans."""
    import math

    from build123d import Face

    def z(x, y):
        ripple = 1.0 * math.sin(x / 60.0 * 8 * math.pi) * math.cos(y / 40.0 * 2 * math.pi) if wavy else 0.0
        return 6.0 * ((x / 60.0) * (1 - x / 60.0) + 0.5 * (y / 40.0) ** 2) + ripple

    step = 2.5 if wavy else 10
    grid = [[(x, y, z(x, y)) for x in _range(0, 60, step)] for y in _range(0, 40, step)]
    spline = Face.make_surface_from_array_of_points(grid).wrapped
    basis = BRep_Tool.Surface_s(spline)
    assert isinstance(basis, Geom_BSplineSurface)
    return BRepBuilderAPI_MakeFace(Geom_OffsetSurface(basis, 1.5), 1e-7).Face()


def test_rays_meet_an_offset_spline_where_the_exact_offset_surface_says():
    face = offset_spline_face()
    exact = BRep_Tool.Surface_s(face)
    assert isinstance(exact, Geom_OffsetSurface)
    targets = TargetFaces({0: face}, reach=20.0)
    assert targets.surfaces[0].locator is not None
    met = 0
    for x, y, dz in [(5, 5, 1.0), (30, 20, -1.0), (55, 35, 1.0), (20, 38, -1.0)]:
        origin = (float(x), float(y), 10.0 if dz < 0 else -8.0)
        direction = (0.3, -0.1, dz)
        scale_ = sum(c * c for c in direction) ** 0.5
        direction = tuple(c / scale_ for c in direction)
        hits = targets.hits(origin, direction, 20.0, [0])
        meet = GeomAPI_IntCS(Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction))), exact)
        expected = sorted(
            d for d in (
                sum((a - b) * c for a, b, c in zip((meet.Point(k).X(), meet.Point(k).Y(), meet.Point(k).Z()), origin, direction))
                for k in range(1, meet.NbPoints() + 1)
            ) if 0.0 < d <= 20.0
        )
        assert [h["distance"] for h in hits] == pytest.approx(expected, abs=1e-8)
        met += len(hits)
    assert met >= 4


def test_a_ray_the_pole_hull_rules_out_meets_nothing_on_the_exact_surface():
    """Random rays at the spline sheet: every one the hull test skips really misses within its reach, and the
    test skips most of those that pass beside the sheet."""
    import random

    from midsurf_sidecar.joints.edge_probe import RaySurface

    face = swept_spline_strip()
    ray_surface = RaySurface(face, reach=30.0)
    assert ray_surface.hull is not None
    rng = random.Random(7)
    skipped = beside = 0
    for _ in range(300):
        origin = (rng.uniform(-20, 60), rng.uniform(-20, 20), rng.uniform(-10, 20))
        direction = [rng.uniform(-1, 1) for _ in range(3)]
        length = sum(c * c for c in direction) ** 0.5
        direction = tuple(c / length for c in direction)
        line = Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction)))
        meet = GeomAPI_IntCS(line, ray_surface.exact)
        within = [
            k for k in range(1, meet.NbPoints() + 1)
            if 0.0 < sum((a - b) * c for a, b, c in zip(xyz_of(meet.Point(k)), origin, direction)) <= 30.0
        ]
        if ray_surface.hull.misses(origin, direction, 30.0):
            skipped += 1
            assert not within
        elif not within:
            beside += 1
    assert skipped > beside


def test_a_spline_sampled_once_meets_random_lines_as_intcs_does():
    """The offset sheet's locator (a spline of many spans, each sampled on its own): random lines through its
    box meet it where GeomAPI_IntCS finds, line by line."""
    import random

    from midsurf_sidecar.joints.edge_probe import RaySurface

    ray_surface = RaySurface(offset_spline_face(wavy=True), reach=20.0)
    locator, sampled = ray_surface.locator, ray_surface.sampled
    assert locator is not None and len(sampled.spans) > 1
    rng = random.Random(11)
    met = 0
    for _ in range(200):
        origin = (rng.uniform(0, 60), rng.uniform(0, 40), rng.uniform(-5, 12))
        direction = [rng.uniform(-1, 1) for _ in range(3)]
        length = sum(c * c for c in direction) ** 0.5
        line = Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*(c / length for c in direction))))
        reference = GeomAPI_IntCS(line, locator)
        expected = sorted(reference.Parameters(k)[2] for k in range(1, reference.NbPoints() + 1))
        assert sorted(w for _, _, w, _ in sampled.meet(line)) == pytest.approx(expected, abs=1e-9)
        met += len(expected)
    assert met >= 50


def _range(start, stop, step):
    return [start + k * step for k in range(int(round((stop - start) / step)) + 1)]


def xyz_of(p):
    return (p.X(), p.Y(), p.Z())


def holed_faces():
    """A 40 x 30 plate with 12 round holes and a square one, and a cylinder's side (its seam used twice)."""
    from build123d import Box, Cylinder, Pos

    plate = Box(40, 30, 2) - Pos(12, 8, 0) * Box(5, 5, 4)
    for i in range(4):
        for j in range(3):
            plate -= Pos(-15 + 8 * i, -10 + 8 * j, 0) * Cylinder(1.5, 4)
    top = max(plate.faces(), key=lambda f: f.center().Z).wrapped
    side = [f for f in Cylinder(5, 8).faces() if f.geom_type.name == "CYLINDER"][0].wrapped
    return [top, side]


def test_the_outward_direction_points_off_the_face_at_every_edge_of_a_face_with_holes():
    """sample_edge's outward side, checked (FaceSides) by the edge's own wire and the outer one: a little inward
    of every sample the kernel's classifier of the whole face says IN, a little outward OUT (seams, with the face
    on both sides, left out)."""
    from OCP.BRepClass import BRepClass_FaceClassifier
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_IN, TopAbs_OUT

    from midsurf_sidecar.joints.edge_probe import FaceSides, sample_edge

    checked = 0
    for face in holed_faces():
        sides = FaceSides(face)
        explorer = TopExp_Explorer(face, TopAbs_EDGE)
        while explorer.More():
            edge = TopoDS.Edge(explorer.Current())
            explorer.Next()
            if BRep_Tool.Degenerated_s(edge) or BRep_Tool.IsClosed_s(edge, face):
                continue
            for sample in sample_edge(face, edge, 5, sides)[1:-1]:
                for sign, expected in ((-1.0, TopAbs_IN), (1.0, TopAbs_OUT)):
                    point = gp_Pnt(*(p + sign * 0.05 * o for p, o in zip(sample.point, sample.outward)))
                    assert BRepClass_FaceClassifier(face, point, 1e-7).State() == expected
                    checked += 1
    assert checked == 2 * 3 * (4 + 4 + 12 + 2)


def test_a_spline_too_large_to_keep_sampled_is_met_ray_by_ray(monkeypatch):
    from midsurf_sidecar.joints import edge_probe

    monkeypatch.setattr(edge_probe, "POLYHEDRON_MAX_POINTS", 100)
    face = offset_spline_face()
    targets = TargetFaces({0: face}, reach=20.0)
    assert targets.surfaces[0].sampled is None
    origin, direction = (30.0, 20.0, 10.0), (0.0, 0.0, -1.0)
    hits = targets.hits(origin, direction, 20.0, [0])
    meet = GeomAPI_IntCS(Geom_Line(gp_Lin(gp_Pnt(*origin), gp_Dir(*direction))), BRep_Tool.Surface_s(face))
    assert [h["distance"] for h in hits] == pytest.approx([10.0 - meet.Point(1).Z()], abs=1e-8)



def test_an_edge_ending_at_a_singular_point_is_sampled_just_short_of_it():
    """Where the face's surface has no derivatives (an offset surface over its basis's pole: OCCT raises
    Geom_UndefinedDerivative), the edge's sample there steps toward the edge's middle: the edge still gets a
    point, a unit normal and an outward direction at each of its samples, the end one close to the corner."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakePolygon
    from OCP.TopAbs import TopAbs_EDGE

    from midsurf_sidecar.geom.vectors import dot, norm
    from midsurf_sidecar.joints.edge_probe import FaceSides, sample_edge

    square = BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 10, 0), gp_Pnt(0, 10, 0), True)
    face = BRepBuilderAPI_MakeFace(square.Wire(), True).Face()
    sides = FaceSides(face)
    exact = sides.surface

    class SingularAtOrigin:
        """The plane, but with no derivatives at the corner (0, 0)."""

        def D1(self, u, v, point, su, sv):
            exact.D1(u, v, point, su, sv)
            if point.Distance(gp_Pnt(0, 0, 0)) < 1e-9:
                raise RuntimeError("Geom_UndefinedDerivative")

        def __getattr__(self, name):
            return getattr(exact, name)

    sides.surface = SingularAtOrigin()
    checked = corner_edges = 0
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        edge = TopoDS.Edge(explorer.Current())
        explorer.Next()
        samples = sample_edge(face, edge, 5, sides)
        assert len(samples) == 5
        for s in samples:
            assert abs(norm(s.normal) - 1.0) < 1e-9 and abs(norm(s.outward) - 1.0) < 1e-9
            assert abs(dot(s.normal, s.outward)) < 1e-9
            checked += 1
        # The two edges at the corner keep a sample within 1% of their length of it.
        corner_edges += min(norm(s.point) for s in samples) < 0.1
    assert checked == 20 and corner_edges == 2


def test_a_point_off_a_face_is_as_far_from_its_nearest_edges_as_from_the_whole_face():
    """FaceEdges measures only to the edges its polylines shortlist: the distances equal BRepExtrema's to the
    whole face, bit for bit, for points of the support surfaces off a holed plate (in its holes and around it)
    and off a half cylinder (past its straight edges and its arcs)."""
    import math
    import random

    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3

    from midsurf_sidecar.joints.edge_probe import FaceEdges

    plate = holed_faces()[0]
    cylinder = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 5.0)
    half = BRepBuilderAPI_MakeFace(cylinder, -math.pi / 2, math.pi / 2, 0.0, 10.0, 1e-7).Face()
    generator = random.Random(7)
    points = {
        id(plate): [(-15 + 1.2 * generator.uniform(-1, 1), -10 + 1.2 * generator.uniform(-1, 1), 1.0)]
        + [(generator.uniform(-30, 30), generator.choice([-1, 1]) * generator.uniform(16, 25), 1.0) for _ in range(20)],
        id(half): [xyz_of(cylinder.Value(generator.uniform(1.7, 4.6), generator.uniform(-3, 13))) for _ in range(20)]
        + [xyz_of(cylinder.Value(generator.uniform(-1.5, 1.5), generator.choice([-2.0, 12.5]))) for _ in range(10)],
    }
    for face in (plate, half):
        edges = FaceEdges(face, 4.5e-4)
        for point in points[id(face)]:
            exact = BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(gp_Pnt(*point)).Vertex(), face).Value()
            assert edges.distance(point) == exact


def test_a_meeting_on_the_far_side_of_a_half_cylinder_is_off_the_face():
    """A half cylinder (r = 5 about z, the half x >= 0, z from 0 to 10) met by a ray along x at y = 3: where it
    enters the cylinder (x = -4) the surface is off the face, whose nearest edge is the line x = 0, y = 5; the
    face's own parameters there lie outside it. (Classified from the 3D point, OCCT projects it on the face's
    parameter range and finds the opposite point, x = 4, which is on the face: a gap of 0 that joined edges to
    faces they never reach.) Where it leaves (x = 4) the meeting is on the face."""
    import math

    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3

    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 5.0)
    face = BRepBuilderAPI_MakeFace(surface, -math.pi / 2, math.pi / 2, 0.0, 10.0, 1e-7).Face()
    targets = TargetFaces({0: face}, reach=20.0)
    # At y = -3 the meeting on the face has u = 5.64 from the intersector, the face's -0.64 a turn on.
    for y in (3.0, -3.0):
        hits = targets.hits((-10.0, y, 5.0), (1.0, 0.0, 0.0), 20.0, [0])
        assert [h["distance"] for h in hits] == pytest.approx([6.0, 14.0])
        assert hits[0]["gap"] == pytest.approx(math.hypot(4.0, 2.0), abs=1e-9)
        assert hits[1]["gap"] == 0.0
