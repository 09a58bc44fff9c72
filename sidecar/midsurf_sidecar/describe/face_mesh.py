"""Triangle meshes of a solid's faces: CCW seen from outside, with outward surface normals at the nodes."""

from typing import Any

from OCP.BRep import BRep_Tool
from OCP.BRepLib import BRepLib_ToolTriangulatedShape
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from ..constants import MESH_ANGULAR_DEFLECTION, MIN_RELATIVE_MESH_TOLERANCE
from ..geom.face_meshing import has_many_wires, mesh_delabella
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
        if has_many_wires(face):
            mesh_delabella(face, tolerance, MESH_ANGULAR_DEFLECTION)
        explorer.Next()
    # Faces meshed above keep their triangulation (BRepMesh keeps a mesh as fine as asked), and so do the
    # discretised edges their neighbours share with them.
    mesher = BRepMesh_IncrementalMesh(shape, tolerance, False, MESH_ANGULAR_DEFLECTION, False)
    if not mesher.IsDone():
        raise KernelError(f"BRepMesh_IncrementalMesh failed (tolerance {tolerance} mm)")


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
