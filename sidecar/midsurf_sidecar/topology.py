"""Indexed sub-shape maps and mass properties: the id and measurement conventions shared by all ops."""

from OCP.BRepGProp import BRepGProp
from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as IndexedShapeMap
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_ShapeEnum
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS_Shape


def indexed_map(shape: TopoDS_Shape, kind: TopAbs_ShapeEnum) -> IndexedShapeMap:
    """Sub-shapes of `kind` in TopExp order; id = map index - 1, stable across re-reads of the same file."""
    shape_map = IndexedShapeMap()
    TopExp.MapShapes_s(shape, kind, shape_map)
    return shape_map


def volume(shape: TopoDS_Shape) -> float:
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def surface_props(shape: TopoDS_Shape) -> GProp_GProps:
    """Area (Mass) and centroid (CentreOfMass) of the faces of `shape`."""
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props
