"""STEP import (solids as handles) and XCAF export (per-face names, colours, thickness)."""

import os
import re
from dataclasses import dataclass

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.Message import Message_ProgressRange
from OCP.Quantity import Quantity_Color, Quantity_TOC_sRGB
from OCP.RWGltf import RWGltf_CafWriter
from OCP.RWMesh import RWMesh_CoordinateSystem_Zup
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader
from OCP.collections import IndexedDataMap_TCollection_AsciiString_TCollection_AsciiString as FileInfo
from OCP.TCollection import TCollection_AsciiString, TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name, TDataStd_NamedData
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopoDS import TopoDS_Shape
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_ColorSurf, XCAFDoc_DocumentTool

from .errors import BadArgs, OpError
from .topology import indexed_map

FIXED_TIME_STAMP = "1970-01-01T00:00:00"


@dataclass(frozen=True)
class FaceAttributes:
    """What write_step attaches to one face (index into MapShapes(shape, FACE))."""

    face: int
    name: str | None
    color: tuple[float, float, float] | None
    thickness: float | None


def load_step(path: str) -> list[TopoDS_Shape]:
    """Solids of the STEP file at `path`, in TopExp order; OpError with the protocol code otherwise."""
    return load_step_checked(path)[0]


def load_step_checked(path: str) -> tuple[list[TopoDS_Shape], list[dict]]:
    """`load_step`, and the reader's problems with single entities (`entity_problems`)."""
    if not os.path.exists(path):
        raise OpError("no such file", "not_found")
    if not os.path.isfile(path):
        kind = "a directory" if os.path.isdir(path) else "not a regular file"
        raise OpError(f"is {kind}; pass the path of a .step file", "not_a_file")
    if not os.access(path, os.R_OK):
        raise OpError("cannot read: permission denied", "read_failed")

    reader = STEPControl_Reader()
    status = reader.ReadFile(path)
    # After a failed ReadFile the reader's model is unusable: even NbRootsForTransfer segfaults.
    if status != IFSelect_RetDone:
        empty = " (the file is empty)" if os.path.getsize(path) == 0 else ""
        raise OpError(
            f"not a readable STEP file{empty} (reader status {status.name}); "
            "check that it is a complete STEP (ISO 10303-21) file",
            "read_failed",
        )
    problems = entity_problems(reader, path)
    # A shape broken by a corrupt entity is reported with that entity, the cause.
    first = ([p for p in problems if p["used"]] + problems)[:1]
    cause = f"; the reader failed on entity #{first[0]['entity']}: {first[0]['message']}" if first else ""
    reader.TransferRoots()
    shape = reader.OneShape()
    if reader.NbShapes() == 0 or shape.IsNull():
        raise OpError(f"holds no transferable shape, no solid{cause}", "no_solid")

    solids = indexed_map(shape, TopAbs_SOLID)
    if solids.Size() == 0:
        raise OpError(f"has {_content_summary(shape)}, no solid{cause}", "no_solid")
    return [solids.FindKey(i) for i in range(1, solids.Size() + 1)], problems


# What the reader's checks say per entity, cut to this many entities (a file broken throughout says so in a
# few): enough to find them in the file.
MAX_ENTITY_PROBLEMS = 20
_DEFINITION = re.compile(rb"^\s*#(\d+)\s*=", re.MULTILINE)
_REFERENCE = re.compile(rb"#(\d+)")


def entity_problems(reader: STEPControl_Reader, path: str) -> list[dict]:
    """The reader's syntax and reference failures, per entity: its number in the file (#N), the messages, and
    whether another entity refers to it (then what it stands for, a point or a curve of the shape, is
    missing from the shape; a stray entity nothing refers to is harmless). Empty for a clean file."""
    checks = reader.WS().ModelCheckList()
    failed: list[tuple[int, list[str]]] = []
    checks.Start()
    while checks.More():
        check, number = checks.Value(), checks.Number()
        fails = [str(check.CFail(i)) for i in range(1, check.NbFails() + 1)]
        if fails:
            failed.append((number, fails))
        checks.Next()
    if not failed:
        return []
    with open(path, "rb") as f:
        text = f.read()
    data = text.find(b"DATA;")
    body = text[data:] if data >= 0 else text
    # The model numbers entities in the order the DATA section defines them.
    ids = [int(m.group(1)) for m in _DEFINITION.finditer(body)]
    referenced = {int(m.group(1)) for m in _REFERENCE.finditer(_DEFINITION.sub(b"", body))}
    # The model's own check (number 0) is the header's (a FILE_NAME field of the wrong type: no matter to the
    # shape) or repeats what the entities' checks say, without saying which: left out.
    failed = [(number, fails) for number, fails in failed if number > 0]
    if not failed:
        return []
    problems = []
    for number, fails in failed[:MAX_ENTITY_PROBLEMS]:
        entity = ids[number - 1] if 0 < number <= len(ids) else None
        problems.append({
            "entity": entity,
            "message": " ".join("; ".join(fails).split()),
            "used": entity is not None and entity in referenced,
        })
    return problems


def _content_summary(shape: TopoDS_Shape) -> str:
    """What a solid-less shape holds, e.g. "3 faces, 1 open shell"."""
    shells = indexed_map(shape, TopAbs_SHELL)
    closed = sum(1 for i in range(1, shells.Size() + 1) if BRep_Tool.IsClosed_s(shells.FindKey(i)))
    faces = indexed_map(shape, TopAbs_FACE).Size()
    counts = [(faces, "face"), (shells.Size() - closed, "open shell"), (closed, "closed shell")]
    if faces == 0:
        # A wireframe: say what little it holds.
        counts += [
            (indexed_map(shape, TopAbs_EDGE).Size(), "edge"),
            (indexed_map(shape, TopAbs_VERTEX).Size(), "vertex"),
        ]
    return ", ".join(_count(n, noun) for n, noun in counts if n > 0) or "nothing"


def _count(n: int, noun: str) -> str:
    plural = "vertices" if noun == "vertex" else noun + "s"
    return f"{n} {noun if n == 1 else plural}"


def write_step(path: str, shape: TopoDS_Shape, faces: list[FaceAttributes], preview: str | None = None) -> int:
    """Writes `shape` with XCAF attributes to exactly `path` (and, with `preview`, a GLB of the same document
    there); returns the STEP file size in bytes."""
    for target in [path] + ([preview] if preview else []):
        directory = os.path.dirname(os.path.abspath(target))
        if not os.path.isdir(directory):
            raise OpError(f"cannot write {target}: directory {directory} does not exist", "write_failed")

    STEPCAFControl_Controller.Init_s()
    # Without this the writer drops the names of sub-shape (face) labels.
    Interface_Static.SetIVal_s("write.stepcaf.subshapes.name", 1)
    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    XCAFApp_Application.GetApplication_s().InitDocument(doc)
    _attach_attributes(doc, shape, faces)

    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    writer.SetColorMode(True)
    writer.SetMetadataMode(True)
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise OpError(f"STEPCAFControl_Writer could not transfer the shape for {path}", "write_failed")
    # The header's FILE_NAME carries the time of writing: fixed, so equal requests give equal bytes.
    APIHeaderSection_MakeHeader(writer.ChangeWriter().Model()).SetTimeStamp(
        TCollection_HAsciiString(FIXED_TIME_STAMP)
    )
    status = writer.Write(path)
    if status != IFSelect_RetDone or not os.path.isfile(path):
        raise OpError(f"STEP writer returned {status.name} for {path}", "write_failed")
    if preview:
        # After the STEP, so the triangulation made here cannot change what the STEP writer sees.
        _write_glb(preview, doc, shape)
    return os.path.getsize(path)


def _write_glb(path: str, doc: TDocStd_Document, shape: TopoDS_Shape) -> None:
    """A binary glTF of the document, faces coloured as in the STEP: a preview for any glTF viewer."""
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    diagonal = 1.0 if box.IsVoid() else box.CornerMin().Distance(box.CornerMax())
    # A chordal deflection of 1/1000 of the part's size: smooth enough to look at, small enough to open.
    BRepMesh_IncrementalMesh(shape, max(diagonal * 1e-3, 1e-4), False, 0.3, False)
    writer = RWGltf_CafWriter(TCollection_AsciiString(path), True)
    # glTF is Y-up in metres; STEP here is Z-up in millimetres.
    converter = writer.ChangeCoordinateSystemConverter()
    converter.SetInputLengthUnit(0.001)
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
