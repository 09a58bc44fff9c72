"""load.reanchor: faces whose parametric origin lies far away get one at the face, the shape itself unchanged."""

import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_VERTEX
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from midsurf_sidecar.geom.topology import surface_props
from midsurf_sidecar.load.reanchor import reanchored, translate_parameters
from midsurf_sidecar.load.step_reader import load_step

from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut

from shapes import bent_sheet, cone, plate_with_hole, shaft, write_step

# Half a kilometre: where a CAD export placed every cylinder's axis point in a 40 mm part.
FAR = 5e5


def tube():
    """A tube 2 thick: its bore is a reversed cylinder face with a seam (OCCT swaps a seam's pcurves there)."""
    return BRepAlgoAPI_Cut(shaft(5.0, 20.0), shaft(3.0, 20.0)).Shape()


def faces(shape):
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        yield TopoDS.Face(explorer.Current())
        explorer.Next()


def farthest_parameter(shape) -> float:
    """The largest |middle of a face's parameter box| over the faces (u of a cylinder or cone is an angle)."""
    worst = 0.0
    for face in faces(shape):
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        worst = max(worst, abs(0.5 * (v0 + v1)), abs(0.5 * (u0 + u1)))
    return worst


def pushed_far(shape):
    """`shape` with every face's parameters moved FAR from the face (the export quirk)."""
    for face in faces(shape):
        translate_parameters(face, -FAR, -FAR)
    return shape


def vertices(shape) -> list[float]:
    explorer = TopExp_Explorer(shape, TopAbs_VERTEX)
    points = []
    while explorer.More():
        points.extend(BRep_Tool.Pnt_s(TopoDS.Vertex(explorer.Current())).Coord())
        explorer.Next()
    return points


def pcurve_gap(shape) -> float:
    """The largest distance, at the middle of each edge of each face, between the edge and its pcurve's point."""
    worst = 0.0
    for face in faces(shape):
        surface = BRep_Tool.Surface_s(face)
        explorer = TopExp_Explorer(face, TopAbs_EDGE)
        while explorer.More():
            edge = TopoDS.Edge(explorer.Current())
            explorer.Next()
            if BRep_Tool.Degenerated_s(edge):
                continue
            first, last = BRep_Tool.Range_s(edge)
            middle = 0.5 * (first + last)
            uv = BRep_Tool.CurveOnSurface_s(edge, face, 0.0, 0.0).Value(middle)
            on_edge = BRep_Tool.Curve_s(edge, 0.0, 0.0).Value(middle)
            worst = max(worst, surface.Value(uv.X(), uv.Y()).Distance(on_edge))
    return worst


@pytest.mark.parametrize(
    "make", [bent_sheet, cone, plate_with_hole, tube], ids=["bend", "cone", "holed_plate", "tube"]
)
def test_far_origins_come_back_to_the_faces_with_the_shape_unchanged(make):
    shape = make()
    area, points = surface_props(shape).Mass(), vertices(shape)
    face_areas = [surface_props(face).Mass() for face in faces(shape)]
    pushed_far(shape)
    assert farthest_parameter(shape) > 0.9 * FAR
    # Each move on its own keeps the shape (two wrong moves could undo each other).
    assert BRepCheck_Analyzer(shape).IsValid()
    assert [surface_props(face).Mass() for face in faces(shape)] == pytest.approx(face_areas)
    reanchored(shape)
    assert farthest_parameter(shape) < 50.0
    assert BRepCheck_Analyzer(shape).IsValid()
    assert surface_props(shape).Mass() == pytest.approx(area, rel=1e-9)
    assert [surface_props(face).Mass() for face in faces(shape)] == pytest.approx(face_areas)
    assert vertices(shape) == pytest.approx(points)
    assert pcurve_gap(shape) < 1e-6


def test_faces_near_their_origin_are_left_as_they_are():
    shape = plate_with_hole()
    before = [BRepTools.UVBounds_s(face) for face in faces(shape)]
    reanchored(shape)
    assert [BRepTools.UVBounds_s(face) for face in faces(shape)] == before


def test_a_file_with_far_origins_loads_with_origins_at_its_faces(tmp_path):
    path = write_step(pushed_far(bent_sheet()), tmp_path / "far.step")
    (solid,) = load_step(str(path))
    assert farthest_parameter(solid) < 50.0
    assert BRepCheck_Analyzer(solid).IsValid()
