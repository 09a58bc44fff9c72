"""A solid and what the patch stage asks of its boundary, each made on first use and kept for the request: a point
classifier, and its faces with their bounding boxes (which of them come near a face)."""

from OCP.Bnd import Bnd_Box
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Lin

from ..constants import ANGULAR, CONFUSION
from .topology import compound_of, indexed_map


class SolidBoundary:
    def __init__(self, shape: TopoDS_Shape):
        self.shape = shape
        self._classifier: BRepClass3d_SolidClassifier | None = None
        self._boxes: list[tuple[TopoDS_Shape, Bnd_Box]] | None = None

    @property
    def classifier(self) -> BRepClass3d_SolidClassifier:
        if self._classifier is None:
            self._classifier = BRepClass3d_SolidClassifier(self.shape)
        return self._classifier

    def faces_near(self, face: TopoDS_Face, margin: float, skins) -> TopoDS_Compound | None:
        """A compound of the solid's faces whose bounding boxes come within `margin` of the face's, of `skins`
        only those that come within `margin` of the face itself (their surfaces' separation first, the exact
        distance only when that says nothing); None when there are none. Boxes from the geometry, not a mesh:
        loose around a B-spline, never short of it."""
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box, False)
        box.Enlarge(max(margin, CONFUSION))
        own = None  # the face's surface, read once for all its skins
        near = []
        for other, other_box in self._face_boxes():
            if box.IsOut(other_box):
                continue
            if any(other.IsSame(s) for s in skins):
                own = BRepAdaptor_Surface(face, True) if own is None else own
                if separation_bound(face, TopoDS.Face(other), own) > margin:
                    continue
                distance = BRepExtrema_DistShapeShape(face, other)
                if distance.IsDone() and distance.Value() > margin:
                    continue
            near.append(other)
        return compound_of(near) if near else None

    def _face_boxes(self) -> list[tuple[TopoDS_Shape, Bnd_Box]]:
        if self._boxes is None:
            faces = indexed_map(self.shape, TopAbs_FACE)
            self._boxes = []
            for i in range(1, faces.Size() + 1):
                box = Bnd_Box()
                BRepBndLib.Add_s(faces.FindKey(i), box, False)
                self._boxes.append((faces.FindKey(i), box))
        return self._boxes


def separation_bound(face: TopoDS_Face, other: TopoDS_Face, own: BRepAdaptor_Surface | None = None) -> float:
    """A lower bound on the distance between two faces from their surfaces alone, 0 when there is none cheaper
    than the exact distance: parallel planes lie their separation apart, cylinders on parallel axes e apart at
    least |r1 - r2| - e apart (a point's distance from one axis changes by at most e on the other). A mid-patch
    and its own skins are such pairs half a wall apart, and the exact distance between curved faces with many
    edges costs a tenth of a second each. Within the kernel's own precision of it (CONFUSION). `own`: the face's
    surface when the caller has it."""
    a = BRepAdaptor_Surface(face, True) if own is None else own
    b = BRepAdaptor_Surface(other, True)
    if a.GetType() == GeomAbs_Plane and b.GetType() == GeomAbs_Plane:
        pa, pb = a.Plane(), b.Plane()
        if not pa.Axis().IsParallel(pb.Axis(), ANGULAR):
            return 0.0
        return pb.Distance(pa.Location()) - CONFUSION
    if a.GetType() == GeomAbs_Cylinder and b.GetType() == GeomAbs_Cylinder:
        ca, cb = a.Cylinder(), b.Cylinder()
        if not ca.Axis().IsParallel(cb.Axis(), ANGULAR):
            return 0.0
        offset = gp_Lin(ca.Axis()).Distance(cb.Location())
        return abs(ca.Radius() - cb.Radius()) - offset - CONFUSION
    return 0.0
