"""Area, centroid and outward normal of a single face: what make_patch and fuse report per face."""

from typing import Any

from OCP.TopoDS import TopoDS_Face

from .face_normals import OutwardNormals
from .face_point import interior_point
from .topology import diagonal, surface_props
from .vectors import xyz


def measure(face: TopoDS_Face) -> dict[str, Any]:
    """`{"area", "centroid", "point", "normal"}`: `point` lies on the face (the centroid of a curved or holed
    face need not), `normal` is the oriented face's normal there."""
    props = surface_props(face)
    point, normal = interior_point(OutwardNormals(face), diagonal(face))
    centroid = list(xyz(props.CentreOfMass()))
    return {"area": props.Mass(), "centroid": centroid, "point": list(point), "normal": list(normal)}
