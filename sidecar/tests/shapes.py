"""Small solids built with OCP for the tests, and a STEP writer for them."""

import math
from pathlib import Path

from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakePolygon,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepPrimAPI import (
    BRepPrimAPI_MakeBox,
    BRepPrimAPI_MakeCone,
    BRepPrimAPI_MakeCylinder,
    BRepPrimAPI_MakePrism,
    BRepPrimAPI_MakeSphere,
    BRepPrimAPI_MakeTorus,
)
from OCP.GC import GC_MakeArcOfCircle
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Vec
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
from OCP.TopoDS import TopoDS_Shape


def box(dx: float = 10.0, dy: float = 20.0, dz: float = 30.0) -> TopoDS_Shape:
    return BRepPrimAPI_MakeBox(dx, dy, dz).Shape()


def extrude_polygon(points: list[tuple[float, float]], height: float) -> TopoDS_Shape:
    """A prism of the closed XY polygon `points`, `height` along +Z."""
    polygon = BRepBuilderAPI_MakePolygon()
    for x, y in points:
        polygon.Add(gp_Pnt(x, y, 0.0))
    polygon.Close()
    face = BRepBuilderAPI_MakeFace(polygon.Wire()).Face()
    return BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, height)).Shape()


# An L of 5 mm arms in a 20 x 20 square: its one re-entrant corner is at (5, 5).
L_PROFILE = [(0.0, 0.0), (20.0, 0.0), (20.0, 5.0), (5.0, 5.0), (5.0, 20.0), (0.0, 20.0)]


def l_extrusion() -> TopoDS_Shape:
    return extrude_polygon(L_PROFILE, 10.0)


def plate_with_hole(radius: float = 5.0) -> TopoDS_Shape:
    """A 40 x 40 x 5 plate with a through hole of `radius` at (20, 20)."""
    plate = BRepPrimAPI_MakeBox(40.0, 40.0, 5.0).Shape()
    axis = gp_Ax2(gp_Pnt(20.0, 20.0, -1.0), gp_Dir(0.0, 0.0, 1.0))
    drill = BRepPrimAPI_MakeCylinder(axis, radius, 7.0).Shape()
    cut = BRepAlgoAPI_Cut(plate, drill)
    assert cut.IsDone(), "the hole cut must succeed"
    return cut.Shape()


def shaft(radius: float = 5.0, length: float = 20.0) -> TopoDS_Shape:
    return BRepPrimAPI_MakeCylinder(radius, length).Shape()


def sphere(radius: float = 5.0) -> TopoDS_Shape:
    return BRepPrimAPI_MakeSphere(radius).Shape()


def torus(major: float = 10.0, minor: float = 2.0) -> TopoDS_Shape:
    return BRepPrimAPI_MakeTorus(major, minor).Shape()


def cone() -> TopoDS_Shape:
    return BRepPrimAPI_MakeCone(5.0, 2.0, 10.0).Shape()


def box_with_void() -> TopoDS_Shape:
    """A 20 mm cube with a spherical void of radius 4 inside: a solid with two shells."""
    void = BRepPrimAPI_MakeSphere(gp_Pnt(10.0, 10.0, 10.0), 4.0).Shape()
    cut = BRepAlgoAPI_Cut(box(20.0, 20.0, 20.0), void)
    assert cut.IsDone(), "the void cut must succeed"
    return cut.Shape()


# Bent sheet: thickness 2, inner bend radius 3 (outer 5), bend axis along Z through (20, 5).
BEND_CENTRE = (20.0, 5.0)
BEND_INNER, BEND_OUTER = 3.0, 5.0


def bent_sheet() -> TopoDS_Shape:
    """An L-bent sheet in XY extruded 10 along Z: flange along X, 90 degree bend, flange along Y."""
    cx, cy = BEND_CENTRE
    diag = math.sqrt(0.5)

    def p(x: float, y: float) -> gp_Pnt:
        return gp_Pnt(x, y, 0.0)

    def line(a: gp_Pnt, b: gp_Pnt):
        return BRepBuilderAPI_MakeEdge(a, b).Edge()

    def arc(a: gp_Pnt, mid: gp_Pnt, b: gp_Pnt):
        return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(a, mid, b).Value()).Edge()

    ro, ri = BEND_OUTER, BEND_INNER
    edges = [
        line(p(0, 0), p(cx, cy - ro)),
        arc(p(cx, cy - ro), p(cx + ro * diag, cy - ro * diag), p(cx + ro, cy)),
        line(p(cx + ro, cy), p(cx + ro, 25)),
        line(p(cx + ro, 25), p(cx + ri, 25)),
        line(p(cx + ri, 25), p(cx + ri, cy)),
        arc(p(cx + ri, cy), p(cx + ri * diag, cy - ri * diag), p(cx, cy - ri)),
        line(p(cx, cy - ri), p(0, cy - ri)),
        line(p(0, cy - ri), p(0, 0)),
    ]
    wire = BRepBuilderAPI_MakeWire()
    for edge in edges:
        wire.Add(edge)
    face = BRepBuilderAPI_MakeFace(wire.Wire()).Face()
    return BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, 10.0)).Shape()


def write_step(shape: TopoDS_Shape, path: Path) -> Path:
    writer = STEPControl_Writer()
    assert writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone, "STEP transfer must succeed"
    assert writer.Write(str(path)) == IFSelect_RetDone, "STEP write must succeed"
    return path
