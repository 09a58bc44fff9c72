"""Plain-tuple 3D vector arithmetic and gp -> JSON conversions (the protocol's points are `[x, y, z]`)."""

import math

from OCP.Bnd import Bnd_Box

Vec = tuple[float, float, float]


def xyz(p) -> Vec:
    """gp_Pnt / gp_Dir / gp_Vec / gp_XYZ as a tuple."""
    return (p.X(), p.Y(), p.Z())


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add_scaled(a: Vec, b: Vec, s: float) -> Vec:
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


def scale(a: Vec, s: float) -> Vec:
    return (s * a[0], s * a[1], s * a[2])


def dot(a: Vec, b: Vec) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Vec) -> float:
    return math.sqrt(dot(a, a))


def radial(point: Vec, origin: Vec, axis: Vec) -> Vec:
    """Component of point - origin perpendicular to the unit `axis`."""
    rel = sub(point, origin)
    return add_scaled(rel, axis, -dot(rel, axis))


def bbox_json(box: Bnd_Box) -> dict[str, list[float]]:
    # Bnd_Box.Get() has no usable binding in OCP 8; the corners do.
    return {"min": list(xyz(box.CornerMin())), "max": list(xyz(box.CornerMax()))}
