"""Triangulating one face the way that scales: OCCT's default 2D mesher slows down sharply with the number of
holes in a face (a sheet with 5,041 holes took 23 s), Delabella does not; so a face with more than MANY_WIRES
wires is meshed with Delabella, any other with the default (whose meshes the rest of the code was made with)."""

from OCP.BRepMesh import (
    BRepMesh_DelabellaMeshAlgoFactory,
    BRepMesh_EdgeDiscret,
    BRepMesh_FaceDiscret,
    BRepMesh_IncrementalMesh,
    BRepMesh_ModelBuilder,
    BRepMesh_ModelHealer,
    BRepMesh_ModelPostProcessor,
    BRepMesh_ModelPreProcessor,
)
from OCP.IMeshTools import IMeshTools_Context
from OCP.TopAbs import TopAbs_WIRE
from OCP.TopoDS import TopoDS_Face, TopoDS_Iterator

from ..constants import MANY_WIRES
from ..protocol.errors import KernelError


def has_many_wires(face: TopoDS_Face) -> bool:
    return wire_count(face) > MANY_WIRES


def wire_count(face: TopoDS_Face) -> int:
    count = 0
    it = TopoDS_Iterator(face)
    while it.More():
        count += it.Value().ShapeType() == TopAbs_WIRE
        it.Next()
    return count


def mesh_face(face: TopoDS_Face, deflection: float, angle: float) -> None:
    """Triangulates `face` (absolute `deflection` mm, `angle` rad, one thread), with Delabella when it has many
    wires. A failure leaves the face without a triangulation, as BRepMesh_IncrementalMesh does."""
    if has_many_wires(face):
        mesh_delabella(face, deflection, angle)
    else:
        BRepMesh_IncrementalMesh(face, deflection, False, angle, False)


def mesh_delabella(face: TopoDS_Face, deflection: float, angle: float) -> None:
    """Triangulates one face as BRepMesh_IncrementalMesh would, but with the Delabella algorithm."""
    # BRepMesh_Context is not wrapped by OCP: the same context, assembled from its parts.
    context = IMeshTools_Context()
    context.SetModelBuilder(BRepMesh_ModelBuilder())
    context.SetEdgeDiscret(BRepMesh_EdgeDiscret())
    context.SetModelHealer(BRepMesh_ModelHealer())
    context.SetPreProcessor(BRepMesh_ModelPreProcessor())
    context.SetFaceDiscret(BRepMesh_FaceDiscret(BRepMesh_DelabellaMeshAlgoFactory()))
    context.SetPostProcessor(BRepMesh_ModelPostProcessor())
    mesher = BRepMesh_IncrementalMesh()
    mesher.SetShape(face)
    params = mesher.ChangeParameters()
    params.Deflection, params.Angle = deflection, angle
    params.Relative, params.InParallel = False, False
    mesher.Perform(context)
    if not mesher.IsDone():
        raise KernelError(f"BRepMesh (Delabella) failed on a face of {wire_count(face)} wires (deflection {deflection} mm)")
