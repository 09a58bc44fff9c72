"""STEP export with XCAF attributes (per-face names, colours, thickness) and the glTF preview of the same
document."""

import os
from dataclasses import dataclass

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.Message import Message_ProgressRange
from OCP.Quantity import Quantity_Color, Quantity_TOC_sRGB
from OCP.RWGltf import RWGltf_CafWriter
from OCP.RWMesh import RWMesh_CoordinateSystem_Zup
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs
from OCP.collections import IndexedDataMap_TCollection_AsciiString_TCollection_AsciiString as FileInfo
from OCP.TCollection import TCollection_AsciiString, TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name, TDataStd_NamedData
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Shape
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_ColorSurf, XCAFDoc_DocumentTool

from .surface_model import merge_surface_models
from ..constants import FIXED_TIME_STAMP, GLTF_INPUT_LENGTH_UNIT, PREVIEW_ANGULAR_DEFLECTION, PREVIEW_MIN_DEFLECTION, PREVIEW_RELATIVE_DEFLECTION
from ..geom.topology import indexed_map
from ..protocol.errors import BadArgs, OpError


@dataclass(frozen=True)
class FaceAttributes:
    """What write_step attaches to one face (index into MapShapes(shape, FACE))."""

    face: int
    name: str | None
    color: tuple[float, float, float] | None
    thickness: float | None


def write_step(
    path: str,
    shape: TopoDS_Shape,
    faces: list[FaceAttributes],
    preview: str | None = None,
    solids: list[tuple[str, TopoDS_Shape]] | None = None,
) -> int:
    """Writes `shape` with XCAF attributes to exactly `path` (and, with `preview`, a GLB of the same document
    there); `solids` (name, solid) follow as shapes of their own, so the faces of `shape` keep their indices.
    Returns the STEP file size in bytes."""
    for target in [path] + ([preview] if preview else []):
        directory = os.path.dirname(os.path.abspath(target))
        if not os.path.isdir(directory):
            raise OpError(f"cannot write {target}: directory {directory} does not exist", "write_failed")

    STEPCAFControl_Controller.Init_s()
    # Without this the writer drops the names of sub-shape (face) labels.
    Interface_Static.SetIVal_s("write.stepcaf.subshapes.name", 1)
    # Shells that share edges (manifold shells meeting at T-joints) are written sharing them; the default mode
    # writes each shell's edges anew.
    Interface_Static.SetIVal_s("write.step.nonmanifold", 1)
    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    XCAFApp_Application.GetApplication_s().InitDocument(doc)
    _attach_attributes(doc, shape, faces)
    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    for name, solid in solids or []:
        TDataStd_Name.Set_s(shape_tool.AddShape(solid, False), TCollection_ExtendedString(name))

    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    writer.SetColorMode(True)
    writer.SetMetadataMode(True)
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise OpError(f"STEPCAFControl_Writer could not transfer the shape for {path}", "write_failed")
    APIHeaderSection_MakeHeader(writer.ChangeWriter().Model()).SetTimeStamp(
        TCollection_HAsciiString(FIXED_TIME_STAMP)
    )
    status = writer.Write(path)
    if status != IFSelect_RetDone or not os.path.isfile(path):
        raise OpError(f"STEP writer returned {status.name} for {path}", "write_failed")
    merge_surface_models(path)
    if preview:
        # After the STEP, so the triangulation made here cannot change what the STEP writer sees.
        _write_glb(preview, doc, shape)
    return os.path.getsize(path)


def _write_glb(path: str, doc: TDocStd_Document, shape: TopoDS_Shape) -> None:
    """A binary glTF of the document, faces coloured as in the STEP: a preview for any glTF viewer."""
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    diagonal = 1.0 if box.IsVoid() else box.CornerMin().Distance(box.CornerMax())
    deflection = max(diagonal * PREVIEW_RELATIVE_DEFLECTION, PREVIEW_MIN_DEFLECTION)
    BRepMesh_IncrementalMesh(shape, deflection, False, PREVIEW_ANGULAR_DEFLECTION, False)
    writer = RWGltf_CafWriter(TCollection_AsciiString(path), True)
    # glTF is Y-up in metres; STEP here is Z-up in millimetres.
    converter = writer.ChangeCoordinateSystemConverter()
    converter.SetInputLengthUnit(GLTF_INPUT_LENGTH_UNIT)
    converter.SetInputCoordinateSystem(RWMesh_CoordinateSystem_Zup)
    if not writer.Perform(doc, FileInfo(), Message_ProgressRange()):
        raise OpError(f"the glTF writer could not write {path}", "write_failed")


def _attach_attributes(doc: TDocStd_Document, shape: TopoDS_Shape, faces: list[FaceAttributes]) -> None:
    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    color_tool = XCAFDoc_DocumentTool.ColorTool_s(doc.Main())
    root = shape_tool.AddShape(shape, False)
    face_map = indexed_map(shape, TopAbs_FACE)
    for attrs in faces:
        if not 0 <= attrs.face < face_map.Size():
            raise BadArgs(f"face {attrs.face} out of range: the shape has {face_map.Size()} faces")
        label = shape_tool.AddSubShape(root, face_map.FindKey(attrs.face + 1))
        if label.IsNull():
            raise OpError(f"XCAF refused face {attrs.face} as a sub-shape of the shape", "write_failed")
        if attrs.name is not None:
            TDataStd_Name.Set_s(label, TCollection_ExtendedString(attrs.name))
        if attrs.color is not None:
            # sRGB so that the numbers given are the numbers written in COLOUR_RGB.
            color_tool.SetColor(label, Quantity_Color(*attrs.color, Quantity_TOC_sRGB), XCAFDoc_ColorSurf)
        if attrs.thickness is not None:
            # The STEP writer exports named data only for labels that become products (it needs a
            # shape definition representation), so a face label's data would be dropped: keep the
            # thickness on the shape's own label, one real per face.
            TDataStd_NamedData.Set_s(root).SetReal(
                TCollection_ExtendedString(thickness_key(attrs.face)), attrs.thickness
            )


def thickness_key(face: int) -> str:
    """Named-data key of a face's thickness on the written shape's label (and in the STEP file)."""
    return f"thickness face {face}"
