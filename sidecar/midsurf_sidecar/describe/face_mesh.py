"""Triangle meshes of a solid's faces: CCW seen from outside, with outward surface normals at the nodes."""

import os
import tempfile
from typing import Any

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepLib import BRepLib_ToolTriangulatedShape
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_RetDone
from OCP.Poly import Poly_Triangulation
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from ..constants import MESH_ANGULAR_DEFLECTION, MESH_RETRY_ANGLES, MIN_RELATIVE_MESH_TOLERANCE
from ..geom.face_meshing import has_many_wires, mesh_delabella, mesh_face
from ..geom.topology import diagonal, indexed_map
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
    _mesh_again(shape, tolerance)


def _mesh_again(shape: TopoDS_Shape, tolerance: float) -> None:
    """Meshes each face BRepMesh left without a triangulation again on its own: with finer angular deflections
    (MESH_RETRY_ANGLES) until one works, then a healed copy (`_healed_triangulation`). BRepMesh fails now and
    then on a B-spline face at one setting and meshes it at the next (status BRepMesh_Failure; seen at 0.5
    rad, not at 0.1 on the same face). A face that still fails keeps no triangulation."""
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        if BRep_Tool.Triangulation_s(face, TopLoc_Location()) is None:
            for angle in MESH_RETRY_ANGLES:
                mesh_face(face, tolerance, angle)
                if BRep_Tool.Triangulation_s(face, TopLoc_Location()) is not None:
                    break
            else:
                healed = _healed_triangulation(face, tolerance)
                if healed is not None:
                    BRep_Builder().UpdateFace(face, healed)
        explorer.Next()


def _healed_triangulation(face: TopoDS_Face, tolerance: float) -> Poly_Triangulation | None:
    """The triangulation of `face` after a STEP round trip of the face alone, or None. A face whose wire holds
    edges shorter than BRepMesh's minimum size (a few micrometres, left by booleans) fails to mesh as an open,
    self-intersecting wire whatever the settings; the STEP reader's healing merges such edges on the same
    surface, and the healed face meshes. Its triangulation lies on the same surface with the same parameters
    (the writer keeps them), so the face takes it as its own."""
    handle, path = tempfile.mkstemp(suffix=".step")
    os.close(handle)
    try:
        writer = STEPControl_Writer()
        if writer.Transfer(face, STEPControl_AsIs) != IFSelect_RetDone or writer.Write(path) != IFSelect_RetDone:
            return None
        reader = STEPControl_Reader()
        if reader.ReadFile(path) != IFSelect_RetDone or reader.TransferRoots() == 0:
            return None
        faces = TopExp_Explorer(reader.OneShape(), TopAbs_FACE)
        if not faces.More():
            return None
        copy = TopoDS.Face(faces.Current())
        faces.Next()
        if faces.More():
            return None  # split by the reader: no one face to stand for this one
        mesh_face(copy, tolerance, MESH_ANGULAR_DEFLECTION)
        location = TopLoc_Location()
        triangulation = BRep_Tool.Triangulation_s(copy, location)
        return triangulation if triangulation is not None and location.IsIdentity() else None
    finally:
        os.remove(path)


def face_meshes(shape: TopoDS_Shape, tolerance: float) -> dict[str, Any]:
    """The `mesh` answer: the triangles of each face of `shape` (TopExp.MapShapes order) as `describe` gives them
    with a mesh, and none of the rest of the face graph. Measuring what a written mid-surface covers needs its
    triangles only; describing its thousand faces besides (tight boxes, areas, a point inside each, edge
    convexity) took twenty times as long as meshing them. A face the kernel cannot mesh has no triangles, as in
    `describe`."""
    mesh_shape(shape, tolerance)
    face_map = indexed_map(shape, TopAbs_FACE)
    meshes = []
    for i in range(face_map.Size()):
        face = TopoDS.Face(face_map.FindKey(i + 1))
        try:
            meshes.append(face_mesh(face, face.Orientation() == TopAbs_REVERSED))
        except Exception:
            meshes.append(no_mesh())
    return {"faces": meshes}


def no_mesh() -> dict[str, Any]:
    """The mesh of a face the kernel could not mesh: no triangles."""
    return {"vertices": [], "normals": [], "triangles": []}


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
