"""The `surface` entry of a face: kind plus analytic parameters and the convex flag."""

from typing import Any

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.GeomAbs import (
    GeomAbs_BezierSurface,
    GeomAbs_BSplineSurface,
    GeomAbs_Cone,
    GeomAbs_Cylinder,
    GeomAbs_OffsetSurface,
    GeomAbs_Plane,
    GeomAbs_Sphere,
    GeomAbs_SurfaceOfExtrusion,
    GeomAbs_SurfaceOfRevolution,
    GeomAbs_Torus,
)

from ..geom.vectors import Vec, add_scaled, dot, norm, radial, scale, sub, xyz

FREEFORM_KINDS = {
    GeomAbs_BSplineSurface: "bspline",
    GeomAbs_BezierSurface: "bezier",
    GeomAbs_SurfaceOfRevolution: "revolution",
    GeomAbs_SurfaceOfExtrusion: "extrusion",
    GeomAbs_OffsetSurface: "offset",
}


def describe_surface(
    adaptor: BRepAdaptor_Surface, reversed_face: bool, point: Vec, normal: Vec
) -> dict[str, Any]:
    """`point`/`normal`: a point inside the face and the outward normal there, used for `convex`.

    The convex flags compare that outward normal with the radial direction at the point rather than
    trusting the surface parametrisation (which may run either way round).
    """
    kind = adaptor.GetType()
    if kind == GeomAbs_Plane:
        return _plane(adaptor, reversed_face)
    if kind == GeomAbs_Cylinder:
        cylinder = adaptor.Cylinder()
        origin, axis = xyz(cylinder.Location()), xyz(cylinder.Axis().Direction())
        return {"kind": "cylinder", "origin": list(origin), "axis": list(axis), "radius": cylinder.Radius(),
                "convex": dot(normal, radial(point, origin, axis)) > 0}
    if kind == GeomAbs_Cone:
        cone = adaptor.Cone()
        origin, axis = xyz(cone.Location()), xyz(cone.Axis().Direction())
        return {"kind": "cone", "origin": list(origin), "axis": list(axis), "radius": cone.RefRadius(),
                "half_angle": cone.SemiAngle(), "apex": list(xyz(cone.Apex())),
                "convex": dot(normal, radial(point, origin, axis)) > 0}
    if kind == GeomAbs_Sphere:
        sphere = adaptor.Sphere()
        center = xyz(sphere.Location())
        return {"kind": "sphere", "center": list(center), "radius": sphere.Radius(),
                "convex": dot(normal, sub(point, center)) > 0}
    if kind == GeomAbs_Torus:
        return _torus(adaptor, point, normal)
    return {"kind": FREEFORM_KINDS.get(kind, "other")}


def _plane(adaptor: BRepAdaptor_Surface, reversed_face: bool) -> dict[str, Any]:
    position = adaptor.Plane().Position()
    # An indirect (left-handed) gp_Ax3 has its surface normal opposite to its main direction.
    natural = xyz(position.Direction()) if position.Direct() else scale(xyz(position.Direction()), -1.0)
    outward = scale(natural, -1.0) if reversed_face else natural
    return {"kind": "plane", "origin": list(xyz(position.Location())), "normal": list(outward)}


def _torus(adaptor: BRepAdaptor_Surface, point: Vec, normal: Vec) -> dict[str, Any]:
    torus = adaptor.Torus()
    center, axis = xyz(torus.Location()), xyz(torus.Axis().Direction())
    major = torus.MajorRadius()
    out = radial(point, center, axis)
    length = norm(out)
    # On the axis (a degenerate "lemon" torus) the tube centre is undefined; the centre stands in.
    tube_centre = add_scaled(center, out, major / length) if length > 0 else center
    return {"kind": "torus", "center": list(center), "axis": list(axis), "major_radius": major,
            "minor_radius": torus.MinorRadius(), "convex": dot(normal, sub(point, tube_centre)) > 0}
