"""Triangle meshes of a solid's faces: CCW seen from outside, with outward surface normals at the nodes."""

from typing import Any

from OCP.BRep import BRep_Tool
from OCP.BRepLib import BRepLib_ToolTriangulatedShape
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
from OCP.BRepTools import BRepTools
from OCP.IMeshTools import IMeshTools_Context
from OCP.TopAbs import TopAbs_FACE, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Iterator, TopoDS_Shape

from ..constants import MANY_WIRES, MESH_ANGULAR_DEFLECTION, MIN_RELATIVE_MESH_TOLERANCE
from ..geom.topology import diagonal
from ..protocol.errors import BadArgs, KernelError


def mesh_shape(shape: TopoDS_Shape, tolerance: float) -> None:
    """(Re)triangulates every face with linear deflection `tolerance` mm.

    Old triangulations are dropped first: BRepMesh keeps an existing finer mesh, which would make the
    answer depend on earlier requests.
    """
    size = diagonal(shape)
    if tolerance < size * MIN_RELATIVE_MESH_TOLERANCE:
        raise BadArgs(
            f"mesh_tolerance {tolerance} mm is too fine for a part {size:.6g} mm across: "
            f"use at least {size * MIN_RELATIVE_MESH_TOLERANCE:.3g} mm"
        )
    BRepTools.Clean_s(shape)
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        if _wire_count(face) > MANY_WIRES:
            _mesh_delabella(face, tolerance)
        explorer.Next()
    # Faces meshed above keep their triangulation (BRepMesh keeps a mesh as fine as asked), and so do the
    # discretised edges their neighbours share with them.
    mesher = BRepMesh_IncrementalMesh(shape, tolerance, False, MESH_ANGULAR_DEFLECTION, False)
    if not mesher.IsDone():
        raise KernelError(f"BRepMesh_IncrementalMesh failed (tolerance {tolerance} mm)")


def _wire_count(face: TopoDS_Face) -> int:
    count = 0
    it = TopoDS_Iterator(face)
    while it.More():
        count += it.Value().ShapeType() == TopAbs_WIRE
        it.Next()
    return count


def _mesh_delabella(face: TopoDS_Face, tolerance: float) -> None:
    """Triangulates one face as mesh_shape would, but with the Delabella algorithm."""
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
    params.Deflection, params.Angle = tolerance, MESH_ANGULAR_DEFLECTION
    params.Relative, params.InParallel = False, False
    mesher.Perform(context)
    if not mesher.IsDone():
        wires = _wire_count(face)
        raise KernelError(f"BRepMesh (Delabella) failed on a face of {wires} wires (tolerance {tolerance} mm)")


def face_mesh(face: TopoDS_Face, reversed_face: bool) -> dict[str, Any]:
    """The face's triangulation (from mesh_shape) in global coordinates."""
    location = TopLoc_Location()
    tri = BRep_Tool.Triangulation_s(face, location)
    if tri is None:
        raise KernelError("BRepMesh produced no triangulation for this face")
    # Normals from the surface at each node's UV (exact, unlike averaged triangle normals).
    BRepLib_ToolTriangulatedShape.ComputeNormals_s(face, tri)
    moved = not location.IsIdentity()
    trsf = location.Transformation()
    # The triangulation follows the surface's natural orientation; a REVERSED face turns it inside out.
    sign = -1.0 if reversed_face else 1.0

    vertices, normals = [], []
    for i in range(1, tri.NbNodes() + 1):
        p, n = tri.Node(i), tri.Normal(i)
        if moved:
            p, n = p.Transformed(trsf), n.Transformed(trsf)
        vertices.append([p.X(), p.Y(), p.Z()])
        normals.append([sign * n.X(), sign * n.Y(), sign * n.Z()])

    triangles = []
    for i in range(1, tri.NbTriangles() + 1):
        a, b, c = tri.Triangle(i).Get()
        triangles.append([a - 1, c - 1, b - 1] if reversed_face else [a - 1, b - 1, c - 1])
    return {"vertices": vertices, "normals": normals, "triangles": triangles}
