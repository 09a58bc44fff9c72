"""Hand-made mid-patches (compounds of planar rectangles) for the fuse and make_shells tests."""

from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
from OCP.gp import gp_Pnt
from OCP.TopoDS import TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from midsurf_sidecar.geom.topology import compound_of

Point = tuple[float, float, float]


def rectangle(*corners: Point) -> TopoDS_Face:
    """A planar face through 4 corners; its normal follows them counter-clockwise (right-hand rule)."""
    polygon = BRepBuilderAPI_MakePolygon()
    for corner in corners:
        polygon.Add(gp_Pnt(*corner))
    polygon.Close()
    return BRepBuilderAPI_MakeFace(polygon.Wire(), True).Face()


def compound(*shapes: TopoDS_Shape) -> TopoDS_Compound:
    return compound_of(list(shapes))


def horizontal() -> TopoDS_Face:
    """z = 1 over x in [0, 60], y in [0, 40]; normal +z."""
    return rectangle((0, 0, 1), (60, 0, 1), (60, 40, 1), (0, 40, 1))


def vertical(x: float, z0: float = 0.0) -> TopoDS_Face:
    """x = `x` over y in [0, 40], z in [z0, 40]; normal +x (into the L's inside, like horizontal's +z)."""
    return rectangle((x, 0, z0), (x, 40, z0), (x, 40, 40), (x, 0, 40))


def put_patches(client, *faces: TopoDS_Face) -> list[int]:
    """One patch handle per face, as make_patch would return them."""
    return [client.session.store.put(compound(face)) for face in faces]
