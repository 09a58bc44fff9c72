"""offset_face: a face moved along its outward normal."""

from pathlib import Path

from OCP.BOPAlgo import BOPAlgo_Builder
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepTools import BRepTools
from OCP.GeomAbs import GeomAbs_Circle, GeomAbs_Line
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Shape

from midsurf_sidecar.geom.topology import subshapes
from midsurf_sidecar.patch.face_offset import offset_face

DATA = Path(__file__).parent / "data"


def largest_edge_tolerance(shape):
    return max(BRep_Tool.Tolerance_s(TopoDS.Edge(e)) for e in subshapes(shape, TopAbs_EDGE))


def test_a_drafted_corner_s_offset_meets_its_wall_s_offset_along_an_exact_edge():
    # A drafted housing's rounded corner: the inner skin of the corner (a quarter cone, 3 degrees) and the outer
    # skin of the wall beside it (see data/README.md), both offset half the wall (0.5678) into the material: the
    # two mid-patches meet along one of the cone's lines. Made by OCCT's offset, the cone's edges were
    # approximated curves, and fused with the wall (fuzzy 1.7e-4, as the patches are) their common edge came out
    # 0.016 off both faces. On the cone's own (u, v) box the edges are its exact lines and circles, and the fused
    # edge stays within the fuzzy value (7e-5: the wall's offset edges are approximated too, but it is flat).
    skins = TopoDS_Shape()
    BRepTools.Read_s(skins, str(DATA / "drafted_corner_skins.brep"), BRep_Builder())
    corner, wall = (TopoDS.Face(f) for f in subshapes(skins, TopAbs_FACE))
    cone = offset_face(corner, -0.5678)
    kinds = sorted(BRepAdaptor_Curve(TopoDS.Edge(e)).GetType().name for e in subshapes(cone, TopAbs_EDGE))
    assert kinds == sorted(k.name for k in (GeomAbs_Line, GeomAbs_Line, GeomAbs_Circle, GeomAbs_Circle))
    builder = BOPAlgo_Builder()
    for face in (offset_face(wall, -0.5678), cone):
        builder.AddArgument(face)
    builder.SetFuzzyValue(1.7e-4)
    builder.SetNonDestructive(True)
    builder.Perform()
    assert largest_edge_tolerance(builder.Shape()) < 1.7e-4
