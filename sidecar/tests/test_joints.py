"""probe_edges, extend_edges and gather: a T joint made by growing the rib's free edge down to the base."""

import math

import pytest
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeVertex
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone, BRepPrimAPI_MakeCylinder
from OCP.Bnd import Bnd_Box
from OCP.Geom import Geom_CylindricalSurface
from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Cone, GeomAbs_Cylinder, GeomAbs_Line
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Ax2, gp_Ax3, gp_Dir, gp_Pnt

from midsurf_sidecar.geom.booleans import general_fuse
from midsurf_sidecar.geom.topology import subshapes, surface_props
from midsurf_sidecar.joints.edge_strip import corner, strip
from patch_shapes import horizontal, put_patches, rectangle
from test_fuse import fuse


def rib(z0: float):
    """x = 30 over y in [0, 40], z in [z0, 40]."""
    return rectangle((30, 0, z0), (30, 40, z0), (30, 40, 40), (30, 0, 40))


def free_edge_of(fused, patch, z):
    """(edge, face) of the free edge of `patch` lying at height z."""
    for i, face in enumerate(fused["faces"]):
        if face["patch"] != patch:
            continue
        for e in face["edges"]:
            edge = fused["edges"][e]
            if len(edge["faces"]) == 1 and all(p[2] == pytest.approx(z) for p in edge["points"]):
                return e, i
    raise AssertionError(f"no free edge of patch {patch} at z={z}")


def test_rib_edge_reaches_base_then_strip_shares_the_t_edge(client):
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    targets = list(range(len(fused["faces"])))
    reply = client.ok(
        "probe_edges", handle=fused["handle"], edges=[{"edge": edge, "face": face}], targets=targets, samples=5, reach=3.0
    )
    (probe,) = reply["edges"]
    assert len(probe["points"]) == 5
    for outward, hits in zip(probe["outward"], probe["hits"]):
        assert outward == pytest.approx([0, 0, -1], abs=1e-12)
        assert hits[0]["distance"] == pytest.approx(1.0)
        assert hits[0]["gap"] == pytest.approx(0.0)
        assert fused["faces"][hits[0]["face"]]["patch"] == 0

    strips = client.ok("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.25] * 5}])
    assert strips["strips"] == [{"area": pytest.approx(1.25 * 40), "error": None}]
    rib_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 1]
    base_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 0]
    base = client.ok("gather", parts=[{"handle": fused["handle"], "faces": base_faces}])
    grown = client.ok("gather", parts=[{"handle": fused["handle"], "faces": rib_faces}, {"handle": strips["handle"], "faces": [0]}])
    assert grown["faces"] == 2
    again = fuse(client, [base["handle"], grown["handle"]])
    # The base is split in two along x = 30, the strip into the part above it and a 0.25 overshoot.
    areas = sorted((f["patch"], round(f["area"], 6)) for f in again["faces"])
    assert areas == [(0, 1200), (0, 1200), (1, 10), (1, 40), (1, 38 * 40)]
    t_edges = [e for e in again["edges"] if len(e["faces"]) == 4]
    assert len(t_edges) == 1 and t_edges[0]["length"] == pytest.approx(40.0)


def test_gather_unify_merges_a_strip_into_its_patch(client):
    """With `unify`, the rib's face and the strip grown in its plane become one face (as the stitching gathers a
    patch's pieces); without it they stay two."""
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    strips = client.ok("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.25] * 5}])
    rib_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 1]
    parts = [{"handle": fused["handle"], "faces": rib_faces}, {"handle": strips["handle"], "faces": [0]}]
    assert client.ok("gather", parts=parts)["faces"] == 2
    merged = client.ok("gather", parts=parts, unify=1e-4)
    assert merged["faces"] == 1
    (merged_face,) = fuse(client, [merged["handle"]])["faces"]
    assert merged_face["area"] == pytest.approx(38 * 40 + 1.25 * 40)


def test_outward_points_away_from_the_face_whatever_the_edge_orientation(client):
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    # Each free edge of the base (x = 0, x = 60, y = 0, y = 40) points out of the rectangle.
    expected = {(0, None): [-1, 0, 0], (60, None): [1, 0, 0], (None, 0): [0, -1, 0], (None, 40): [0, 1, 0]}
    seen = 0
    for i, face in enumerate(fused["faces"]):
        if face["patch"] != 0:
            continue
        for e in face["edges"]:
            points = fused["edges"][e]["points"]
            for (x, y), outward in expected.items():
                on = all(p[0] == pytest.approx(x) for p in points) if x is not None else all(p[1] == pytest.approx(y) for p in points)
                if not on:
                    continue
                reply = client.ok("probe_edges", handle=fused["handle"], edges=[{"edge": e, "face": i}], targets=[], samples=3, reach=3.0)
                (probe,) = reply["edges"]
                assert probe["outward"] == [pytest.approx(outward, abs=1e-12)] * 3
                assert probe["hits"] == [[], [], []]
                seen += 1
    assert seen == 4


def test_strip_needs_positive_lengths(client):
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    reply = client.request("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.0, 0.0]}])
    assert reply["err"]["code"] == "bad_args"


def test_an_edge_swept_along_a_vector_makes_an_upright_band_or_a_ramp(client):
    """`along` (a step between two levels whose edges are one curve): lengths of 0 sweep the rib's foot straight
    by the vector, positive lengths make a ramp to the samples moved outward and by the vector."""
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    upright = {"edge": edge, "face": face, "lengths": [0.0] * 5, "along": [0.5, 0.0, 0.0]}
    ramp = {"edge": edge, "face": face, "lengths": [0.5] * 5, "along": [0.5, 0.0, 0.0]}
    reply = client.ok("extend_edges", handle=fused["handle"], strips=[upright, ramp])
    areas = [made["area"] for made in reply["strips"]]
    assert areas == [pytest.approx(40 * 0.5), pytest.approx(40 * math.hypot(0.5, 0.5))]
    (band, slope) = fuse(client, [reply["handle"]])["faces"]
    # The band lies in z = 2 from x = 30 to 30.5; the ramp runs down to z = 1.5 at x = 30.5.
    assert band["centroid"] == pytest.approx([30.25, 20.0, 2.0])
    assert slope["centroid"] == pytest.approx([30.25, 20.0, 1.75])


def side_and_foot(solid, kind):
    """The lateral face of a solid of revolution standing on z = 0 (the face of surface `kind`) and its foot:
    the circle edge at z = 0."""
    faces = TopExp_Explorer(solid, TopAbs_FACE)
    while BRepAdaptor_Surface(TopoDS.Face(faces.Current())).GetType() != kind:
        faces.Next()
    side = TopoDS.Face(faces.Current())
    edges = TopExp_Explorer(side, TopAbs_EDGE)
    while edges.More():
        edge = TopoDS.Edge(edges.Current())
        curve = BRepAdaptor_Curve(edge)
        if curve.GetType() == GeomAbs_Circle and curve.Value(curve.FirstParameter()).Z() == pytest.approx(0.0):
            return side, edge
        edges.Next()
    raise AssertionError("no foot circle at z = 0")


def test_a_tube_end_grows_along_its_own_cylinder():
    """A circle edge of a cylindrical patch grown along the axis stays on the patch's cylinder (so it merges
    into the patch), not a ruled or extruded surface."""
    side, bottom = side_and_foot(BRepPrimAPI_MakeCylinder(2.0, 5.0).Shape(), GeomAbs_Cylinder)
    grown = strip(side, bottom, [1.5] * 5)
    assert BRepAdaptor_Surface(grown).GetType() == GeomAbs_Cylinder
    assert surface_props(grown).Mass() == pytest.approx(2 * math.pi * 2.0 * 1.5)
    box_z = [BRepAdaptor_Surface(grown).Value(0.0, v).Z() for v in (BRepAdaptor_Surface(grown).FirstVParameter(), BRepAdaptor_Surface(grown).LastVParameter())]
    assert sorted(box_z) == pytest.approx([-1.5, 0.0])


def test_a_saddle_edge_grown_onto_a_face_is_a_band_of_its_own_cylinder():
    """A branch tube (radius 2 about z) standing on a main tube (radius 5 about x) ends in a saddle edge (z from
    sqrt(21) to 5; the seam splits it in two halves). Grown onto the main's face by lengths that vary along it,
    the strip is the band of the branch's own cylinder from the saddle down past its lowest point by the
    longest length, which meets the main's cylinder analytically; without `onto_face` it is a ruled surface."""
    branch = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2.0, 10.0).Shape()
    main = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-10, 0, 0), gp_Dir(1, 0, 0)), 5.0, 20.0).Shape()
    faces = TopExp_Explorer(BRepAlgoAPI_Cut(branch, main).Shape(), TopAbs_FACE)
    while BRepAdaptor_Surface(TopoDS.Face(faces.Current())).GetType() != GeomAbs_Cylinder:
        faces.Next()
    side = TopoDS.Face(faces.Current())
    saddles = []
    edges = TopExp_Explorer(side, TopAbs_EDGE)
    while edges.More():
        edge = TopoDS.Edge(edges.Current())
        curve = BRepAdaptor_Curve(edge)
        if curve.GetType() != GeomAbs_Line and curve.Value(curve.FirstParameter()).Z() < 9.0:
            saddles.append(edge)
        edges.Next()
    assert len(saddles) == 2
    lengths = [1.0, 1.2, 1.4, 1.2, 1.0]
    grown = strip(side, saddles[0], lengths, onto_face=True)
    assert BRepAdaptor_Surface(grown).GetType() == GeomAbs_Cylinder
    assert BRepCheck_Analyzer(grown).IsValid()
    box = Bnd_Box()
    BRepBndLib.Add_s(grown, box)
    low = math.sqrt(21.0) - max(lengths)
    assert [box.CornerMin().Z(), box.CornerMax().Z()] == pytest.approx([low, 5.0], abs=1e-5)
    # Half the branch's circumference, from `low` up to the saddle z = sqrt(25 - y^2), y = 2 sin(a).
    steps = 2000
    angles = [math.pi * (k + 0.5) / steps for k in range(steps)]
    band = sum(2.0 * (math.sqrt(25.0 - (2.0 * math.sin(a)) ** 2) - low) * math.pi / steps for a in angles)
    assert surface_props(grown).Mass() == pytest.approx(band, rel=1e-4)
    assert BRepAdaptor_Surface(strip(side, saddles[0], lengths)).GetType() != GeomAbs_Cylinder


def test_a_cone_foot_grows_along_its_own_cone():
    """The foot circle of a conical patch (a drafted boss's mid-surface) grown down its meridian stays on the
    patch's cone, so it merges into the patch: a ruled strip would be a face of its own."""
    # Radius 6 at z = 0 narrowing to 5 at z = 10.
    side, foot = side_and_foot(BRepPrimAPI_MakeCone(6.0, 5.0, 10.0).Shape(), GeomAbs_Cone)
    slant = math.hypot(1.0, 10.0)
    grown = strip(side, foot, [slant / 10.0] * 5)  # down by 1 along the cone: radius 6 -> 6.1
    assert BRepAdaptor_Surface(grown).GetType() == GeomAbs_Cone
    # The frustum from r 6.1 at z = -1 to r 6 at z = 0: pi (r1 + r2) x slant length.
    assert surface_props(grown).Mass() == pytest.approx(math.pi * (6.1 + 6.0) * slant / 10.0, rel=1e-9)


def test_a_step_bridge_between_coaxial_arcs_is_a_band_of_a_cone_sharing_its_arcs():
    # A rim band's mid-surface (radius 10.76 from z = 35.64 up) over a rounded corner's wall (radius 10.39 up to
    # z = 35.64): the ramp from the band's edge down to an arc 0.635 inside the wall's patch, a quarter turn.
    def at(r, angle, z):
        return (r * math.cos(angle), r * math.sin(angle), z)

    quad = [at(10.76, 0.0, 35.64), at(10.39, 0.0, 35.005), at(10.39, math.pi / 2, 35.005), at(10.76, math.pi / 2, 35.64)]
    band = corner(quad, (1.0, 1.0, 0.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
    assert BRepCheck_Analyzer(band).IsValid()
    slant = math.hypot(10.76 - 10.39, 0.635)
    assert surface_props(band).Mass() == pytest.approx(math.pi / 4 * (10.76 + 10.39) * slant, rel=1e-6)
    curves = [BRepAdaptor_Curve(TopoDS.Edge(e)) for e in subshapes(band, TopAbs_EDGE)]
    radii = sorted(round(c.Circle().Radius(), 9) for c in curves if c.GetType() == GeomAbs_Circle)
    assert radii == [10.39, 10.76]


def test_a_step_bridge_whose_arcs_start_where_they_end_is_a_whole_turn_of_a_cone():
    """A stepped bore's ramp: from the thin wall's mid-circle (R 17.25, z = 6) to one RAMP_RUN inside the
    thick wall's (R 16.5, z = 7.25), all round. Each side of the quad starts where it ends; the band is the
    whole turn of the cone between the circles, valid, of area pi (R1 + R2) x slant."""
    quad = [(17.25, 0.0, 6.0), (16.5, 0.0, 7.25), (16.5, 0.0, 7.25), (17.25, 0.0, 6.0)]
    band = corner(quad, (0.0, 0.0, 1.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
    assert BRepCheck_Analyzer(band).IsValid()
    slant = math.hypot(17.25 - 16.5, 1.25)
    assert surface_props(band).Mass() == pytest.approx(math.pi * (17.25 + 16.5) * slant, rel=1e-6)


def test_a_band_between_two_arcs_of_one_cylinder_is_a_face_of_that_cylinder():
    """A gap in a tube's own mid-surface (a rib crossing a boss off its axis) is bridged between the two arcs
    at the ends of the stretch the gap's rulings share: both of radius 3.75, at z = 3 and z = 31.6, from angle
    0 counter-clockwise to 33 degrees. The band is a face of that cylinder (a ruled B-spline would not merge into
    the patch), of area 3.75 x 0.576 x 28.6."""
    def at(angle, z):
        return (3.75 * math.cos(angle), 3.75 * math.sin(angle), z)

    gap = math.radians(33.0)
    quad = [at(0.0, 3.0), at(0.0, 31.6), at(gap, 31.6), at(gap, 3.0)]
    band = corner(quad, (1.0, 0.0, 0.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
    assert BRepCheck_Analyzer(band).IsValid()
    surface = BRepAdaptor_Surface(band)
    assert surface.GetType() == GeomAbs_Cylinder
    assert surface.Cylinder().Radius() == pytest.approx(3.75, abs=1e-9)
    assert surface_props(band).Mass() == pytest.approx(3.75 * gap * 28.6, rel=1e-9)


def test_an_arc_past_the_period_grows_a_strip_the_fuse_keeps_valid():
    """A tube patch whose u range runs from 1.5 pi to 3 pi, its end circle split at u = 2 pi (where another
    face touched it): the arc at u 2 pi..3 pi grows a strip of the tube's own cylinder, which OCCT makes at
    u 0..pi. Fused with the patch, the strip must stay a valid face of positive area: on the patch's very surface
    object it took the patch's pcurve of their shared edge, a period away from its own wire, and came out
    inverted (and in a whole part's fuse, deleted the patch face with it)."""
    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2.0)
    tube = BRepBuilderAPI_MakeFace(surface, 1.5 * math.pi, 3.0 * math.pi, 0.0, 5.0, 1e-7).Face()
    touched = general_fuse([tube, BRepBuilderAPI_MakeVertex(gp_Pnt(2.0, 0.0, 5.0)).Vertex()], 1e-7)
    tube = TopoDS.Face(touched.Modified(tube).First())
    arcs = []
    edges = TopExp_Explorer(tube, TopAbs_EDGE)
    while edges.More():
        edge = TopoDS.Edge(edges.Current())
        pcurve = BRepAdaptor_Curve2d(edge, tube)
        ends = [pcurve.Value(pcurve.FirstParameter()), pcurve.Value(pcurve.LastParameter())]
        if all(p.Y() == pytest.approx(5.0) for p in ends):
            arcs.append((sorted(p.X() for p in ends), edge))
        edges.Next()
    spans = [u for span, _ in sorted(arcs, key=lambda a: a[0]) for u in span]
    assert spans == pytest.approx([1.5 * math.pi, 2.0 * math.pi, 2.0 * math.pi, 3.0 * math.pi])
    strips = [strip(tube, edge, [1.0] * 5) for _, edge in arcs]
    fused = general_fuse([tube, *strips], 1e-5).Shape()
    areas = []
    faces = TopExp_Explorer(fused, TopAbs_FACE)
    while faces.More():
        assert BRepCheck_Analyzer(faces.Current()).IsValid()
        areas.append(surface_props(faces.Current()).Mass())
        faces.Next()
    # The tube (1.5 pi x radius 2 x height 5) and its strips (the same turn, 1 high), none inverted.
    assert min(areas) > 0.0
    assert sum(areas) == pytest.approx(1.5 * math.pi * 2.0 * 6.0)


@pytest.mark.parametrize("settled", [False, True])
def test_a_stitching_pass_fuse_that_skips_settled_intersections_gives_the_same_joint(client, settled):
    """The stitching's own fuse: the rib's kept pieces merged with its strip, then fused again with the base,
    each patch one argument, and the base (untouched since the first fuse) settled or not. It gives what
    intersecting every face with every other gives (the test above)."""
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    strips = client.ok("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.25] * 5}])
    rib_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 1]
    base_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 0]
    base = client.ok("gather", parts=[{"handle": fused["handle"], "faces": base_faces}])
    rib_part = {"handle": fused["handle"], "faces": rib_faces}
    grown = client.ok("gather", parts=[rib_part, {"handle": strips["handle"], "faces": [0]}], unify=1e-6)
    assert grown["faces"] == 1
    again = client.ok(
        "fuse", patches=[base["handle"], grown["handle"]], fuzzy=1e-6, split_internal=True,
        patches_fused=True, settled=[0] if settled else [],
    )
    areas = sorted((f["patch"], round(f["area"], 6)) for f in again["faces"])
    assert areas == [(0, 1200), (0, 1200), (1, 10), (1, 38 * 40 + 40)]
    t_edges = [e for e in again["edges"] if len(e["faces"]) == 4]
    assert len(t_edges) == 1 and t_edges[0]["length"] == pytest.approx(40.0)
