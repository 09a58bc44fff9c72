"""Faces on an offset of a freeform surface with a pole (a freeform dome's mid-patch), which OCCT handles badly
in two ways: its evaluation near the pole is not thread-safe, and its STEP reader drops such a face."""

from OCP.BRep import BRep_Tool
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Geom import Geom_BezierSurface, Geom_BSplineSurface, Geom_OffsetSurface, Geom_RectangularTrimmedSurface
from OCP.ShapeCustom import ShapeCustom
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from ..constants import CONFUSION
from .topology import subshapes


def on_pole_offset(shape: TopoDS_Shape) -> bool:
    """Whether a face of `shape` lies on an offset of a B-spline or Bezier surface with a boundary collapsed to a
    point (a pole: a freeform dome, a surface of revolution meeting its axis). OCCT evaluates such an offset
    near the pole through an osculating surface kept in an NCollection_Sequence, whose lookups move a cursor
    inside it: two threads evaluating the same surface corrupt it. A core dump of a crashed fuse had both
    threads in Geom_OsculatingSurface::VOsculatingSurface (BOPAlgo_PaveFiller::PerformEF); a part with ten
    such skins crashed in 4 of 5 parallel runs, each crash costing a whole serial rerun."""
    for face in subshapes(shape, TopAbs_FACE):
        surface = BRep_Tool.Surface_s(TopoDS.Face(face))
        offset = False  # through any trimmed surfaces between the offset and its basis
        while isinstance(surface, (Geom_RectangularTrimmedSurface, Geom_OffsetSurface)):
            offset = offset or isinstance(surface, Geom_OffsetSurface)
            surface = surface.BasisSurface()
            if offset and isinstance(surface, (Geom_BSplineSurface, Geom_BezierSurface)) and _has_pole(surface):
                return True
    return False


def _has_pole(surface: Geom_BSplineSurface | Geom_BezierSurface) -> bool:
    """Whether a boundary row or column of the surface's poles is one point (within CONFUSION)."""
    nu, nv = surface.NbUPoles(), surface.NbVPoles()
    rows = [[surface.Pole(i, j) for j in range(1, nv + 1)] for i in (1, nu)]
    columns = [[surface.Pole(i, j) for i in range(1, nu + 1)] for j in (1, nv)]
    return any(all(p.Distance(line[0]) <= CONFUSION for p in line) for line in rows + columns)


def as_bspline(face: TopoDS_Face) -> TopoDS_Face:
    """`face`, when it lies on an offset of a freeform surface with a pole, on the B-spline approximation of that
    offset (ShapeCustom, which keeps the face's parameters: within 1e-7 of the offset at the same parameters on a
    dome 60 across); `face` itself otherwise, or when the approximation fails BRepCheck. STEPControl_Reader drops
    such an offset face (a freeform dome's mid-surface was written and read back as nothing), and every later
    boolean with it had to run on one thread (on_pole_offset); its approximation has neither trouble."""
    if not on_pole_offset(face):
        return face
    try:
        converted = subshapes(ShapeCustom.ConvertToBSpline_s(face, False, False, True, False), TopAbs_FACE)
    except Exception:  # OCCT gives up: the offset stays, no worse than before
        return face
    if len(converted) != 1 or not BRepCheck_Analyzer(converted[0]).IsValid():
        return face
    return TopoDS.Face(converted[0])
