"""Area, centroid and outward normal of a single face: what make_patch and fuse report per face."""

from typing import Any

from OCP.TopoDS import TopoDS_Face

from .face_normals import OutwardNormals
from ..protocol.errors import KernelError
from .face_point import edge_point, interior_point
from .topology import diagonal, face_props
from .vectors import xyz


def measure(face: TopoDS_Face, sliver_ok: bool = False) -> dict[str, Any]:
    """`{"area", "centroid", "point", "normal"}`: `point` lies on the face (the centroid of a curved or holed
    face need not), `normal` is the oriented face's normal there. With `sliver_ok`, a face with no point found
    inside it (a sliver a fuse left) is measured at the middle of one of its edges instead of failing."""
    props = face_props(face)
    normals = OutwardNormals(face)
    try:
        point, normal = interior_point(normals, diagonal(face))
    except KernelError:
        if not sliver_ok:
            raise
        point, normal = edge_point(normals)
    centroid = list(xyz(props.CentreOfMass()))
    return {"area": props.Mass(), "centroid": centroid, "point": list(point), "normal": list(normal)}
