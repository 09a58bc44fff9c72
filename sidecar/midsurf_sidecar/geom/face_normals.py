"""Outward normals of a face at (u, v): the surface normal, flipped when the face is REVERSED in the solid."""

from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepLProp import BRepLProp_SLProps
from OCP.TopAbs import TopAbs_REVERSED
from OCP.TopoDS import TopoDS_Face

from ..constants import NORMAL_RESOLUTION
from .vectors import Vec, xyz


class OutwardNormals:
    """Evaluates one face's surface; reuses a single SLProps so repeated queries stay cheap."""

    def __init__(self, face: TopoDS_Face) -> None:
        self.face = face
        self.reversed = face.Orientation() == TopAbs_REVERSED
        # Restricted to the face's UV bounds; the adaptor applies the face location.
        self.adaptor = BRepAdaptor_Surface(face, True)
        self._props = BRepLProp_SLProps(self.adaptor, 1, NORMAL_RESOLUTION)

    def at(self, u: float, v: float) -> tuple[Vec, Vec] | None:
        """(point, outward unit normal) at (u, v), or None where the normal is undefined."""
        self._props.SetParameters(u, v)
        if not self._props.IsNormalDefined():
            return None
        n = xyz(self._props.Normal())
        if self.reversed:
            n = (-n[0], -n[1], -n[2])
        return xyz(self._props.Value()), n
