"""A solid and what the patch stage asks of its boundary, each made on first use and kept for the request: a point
classifier, and its faces with their bounding boxes (which of them come near a face)."""

from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from ..constants import CONFUSION
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
        only those that come within `margin` of the face itself; None when there are none. Boxes from the
        geometry, not a mesh: loose around a B-spline, never short of it."""
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box, False)
        box.Enlarge(max(margin, CONFUSION))
        near = []
        for other, other_box in self._face_boxes():
            if box.IsOut(other_box):
                continue
            if any(other.IsSame(s) for s in skins):
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
