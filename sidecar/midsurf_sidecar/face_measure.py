"""Area, centroid and outward normal of a single face: what make_patch and fuse report per face."""

from typing import Any

from OCP.BRepBndLib import BRepBndLib
from OCP.Bnd import Bnd_Box
from OCP.TopoDS import TopoDS_Face

from .face_normals import OutwardNormals
from .face_point import interior_point
from .topology import surface_props
from .vectors import norm, sub, xyz


def measure(face: TopoDS_Face) -> dict[str, Any]:
    """`{"area", "centroid", "normal"}`; the normal is the oriented face's normal at an interior point."""
    props = surface_props(face)
    _, normal = interior_point(OutwardNormals(face), diagonal(face))
    return {"area": props.Mass(), "centroid": list(xyz(props.CentreOfMass())), "normal": list(normal)}


def diagonal(face: TopoDS_Face) -> float:
    """Bounding-box diagonal; only sizes the fallback mesh of interior_point, so a quick box will do."""
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box, False)
    return norm(sub(xyz(box.CornerMax()), xyz(box.CornerMin())))
