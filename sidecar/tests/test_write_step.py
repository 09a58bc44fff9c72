"""write_step: XCAF export of face names, colours and thickness, read back with STEPCAFControl_Reader."""

import getpass

import pytest
from OCP.BRep import BRep_Builder
from OCP.collections import Sequence_TDF_Label
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.Quantity import Quantity_Color, Quantity_TOC_sRGB
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Reader
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name, TDataStd_NamedData
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Compound
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_ColorSurf, XCAFDoc_DocumentTool, XCAFDoc_ShapeTool

from midsurf_sidecar.write.step_writer import thickness_key
from midsurf_sidecar.geom.topology import indexed_map
from shapes import box


def read_back(path):
    """(face id -> name, face id -> sRGB colour, root named data) of a STEP file read with XCAF."""
    STEPCAFControl_Controller.Init_s()
    Interface_Static.SetIVal_s("read.stepcaf.subshapes.name", 1)
    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    XCAFApp_Application.GetApplication_s().InitDocument(doc)
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    reader.SetColorMode(True)
    reader.SetMetaMode(True)
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    assert reader.Transfer(doc)

    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    color_tool = XCAFDoc_DocumentTool.ColorTool_s(doc.Main())
    roots = Sequence_TDF_Label()
    shape_tool.GetFreeShapes(roots)
    assert roots.Length() == 1
    root = roots.Value(1)
    face_map = indexed_map(XCAFDoc_ShapeTool.GetShape_s(root), TopAbs_FACE)

    names, colors = {}, {}
    subs = Sequence_TDF_Label()
    XCAFDoc_ShapeTool.GetSubShapes_s(root, subs)
    for i in range(1, subs.Length() + 1):
        label = subs.Value(i)
        face = XCAFDoc_ShapeTool.GetShape_s(label)
        face_id = face_map.FindIndex(face) - 1
        # FindAttribute on a label without the attribute segfaults: ask IsAttribute first.
        if label.IsAttribute(TDataStd_Name.GetID_s()):
            name = TDataStd_Name()
            label.FindAttribute(TDataStd_Name.GetID_s(), name)
            names[face_id] = name.Get().ToExtString()
        color = Quantity_Color()
        if color_tool.GetColor(face, XCAFDoc_ColorSurf, color):
            colors[face_id] = color.Values(Quantity_TOC_sRGB)

    data = None
    if root.IsAttribute(TDataStd_NamedData.GetID_s()):
        data = TDataStd_NamedData()
        root.FindAttribute(TDataStd_NamedData.GetID_s(), data)
    return names, colors, data


def test_names_colours_and_thickness_read_back(client, tmp_path):
    handle = client.load(box(), tmp_path)
    path = tmp_path / "out.step"
    faces = [
        {"face": 0, "name": "patch 0 t=2.000", "color": [0.5, 0.25, 0.1], "thickness": 2.0},
        {"face": 4, "name": "patch 4 t=1.500", "thickness": 1.5},
    ]
    ok = client.ok("write_step", path=str(path), handle=handle, faces=faces)
    assert ok == {"path": str(path), "bytes": path.stat().st_size}
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith("out")] == ["out.step"]

    names, colors, data = read_back(path)
    assert names == {0: "patch 0 t=2.000", 4: "patch 4 t=1.500"}
    assert colors == {0: pytest.approx((0.5, 0.25, 0.1), abs=1e-6)}
    assert data is not None
    assert data.GetReal(TCollection_ExtendedString(thickness_key(0))) == 2.0
    assert data.GetReal(TCollection_ExtendedString(thickness_key(4))) == 1.5
    assert not data.HasReal(TCollection_ExtendedString(thickness_key(1)))


def test_no_faces_writes_a_plain_step(client, tmp_path):
    handle = client.load(box(), tmp_path)
    path = tmp_path / "plain.step"
    assert client.ok("write_step", path=str(path), handle=handle, faces=[])["bytes"] > 0
    names, colors, data = read_back(path)
    assert names == {} and colors == {} and data is None
    assert client.ok("load_step", path=str(path))["solids"][0]["faces"] == 6


def test_kept_solids_follow_as_named_solids(client, tmp_path):
    shell = client.load(box(), tmp_path)
    solid = client.load(box(), tmp_path)
    path = tmp_path / "kept.step"
    faces = [{"face": 2, "name": "patch 1 t=2.000"}]
    kept = [{"handle": solid, "name": "solid 2 not_thin_walled"}]
    client.ok("write_step", path=str(path), handle=shell, faces=faces, solids=kept)
    # The first shape keeps its face indices and names; the kept one is a solid of its own.
    assert client.ok("load_step", path=str(path))["solids"][1]["faces"] == 6
    assert "solid 2 not_thin_walled" in path.read_text()
    err = client.err("write_step", path=str(path), handle=shell, faces=[], solids=[{"handle": solid}])
    assert err["code"] == "bad_args"


def test_missing_directory_is_write_failed(client, tmp_path):
    handle = client.load(box(), tmp_path)
    err = client.err("write_step", path=str(tmp_path / "no" / "such" / "dir.step"), handle=handle, faces=[])
    assert err["code"] == "write_failed"


def test_bad_face_arguments(client, tmp_path):
    handle = client.load(box(), tmp_path)
    path = str(tmp_path / "x.step")
    for faces in (
        [{"face": 6}],
        [{"face": -1}],
        [{"name": "no face index"}],
        [{"face": 0, "color": [1, 2, 3]}],
        [{"face": 0, "color": [0.1, 0.2]}],
        [{"face": 0, "thickness": "thick"}],
        [{"face": 0, "name": 7}],
        "all",
    ):
        assert client.err("write_step", path=path, handle=handle, faces=faces)["code"] == "bad_args", faces


def test_identical_requests_give_identical_bytes(client, tmp_path):
    handle = client.load(box(), tmp_path)
    faces = [{"face": 2, "name": "patch 2", "color": [0.1, 0.2, 0.3], "thickness": 0.8}]
    first, second = tmp_path / "first.step", tmp_path / "second.step"
    client.ok("write_step", path=str(first), handle=handle, faces=faces)
    client.ok("write_step", path=str(second), handle=handle, faces=faces)
    text = first.read_text()
    assert first.read_bytes() == second.read_bytes()
    assert "'1970-01-01T00:00:00'" in text
    assert str(tmp_path) not in text and "first" not in text
    assert f"'{getpass.getuser()}'" not in text


def test_empty_compound_gives_a_step_without_geometry(client, tmp_path):
    empty = TopoDS_Compound()
    BRep_Builder().MakeCompound(empty)
    handle = client.session.store.put(empty)
    path = tmp_path / "empty.step"
    assert client.ok("write_step", path=str(path), handle=handle, faces=[])["bytes"] > 0
    assert client.err("load_step", path=str(path))["code"] == "no_solid"


def read_glb(path):
    """The JSON chunk of a binary glTF file, after checking its header and chunk layout."""
    import json
    import struct

    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    chunk_length, chunk_type = struct.unpack_from("<I4s", data, 12)
    assert chunk_type == b"JSON"
    return json.loads(data[20 : 20 + chunk_length])


def test_preview_is_a_glb_with_the_face_colours(client, tmp_path):
    handle = client.load(box(), tmp_path)
    step, glb = tmp_path / "out.step", tmp_path / "out.glb"
    faces = [{"face": i, "name": f"patch {i} t=1.000", "color": [0.1 * i, 0.5, 0.9], "thickness": 1.0} for i in range(6)]
    client.ok("write_step", path=str(step), handle=handle, faces=faces, preview=str(glb))
    gltf = read_glb(glb)
    colours = sorted(tuple(round(c, 3) for c in m["pbrMetallicRoughness"]["baseColorFactor"][:3]) for m in gltf["materials"])
    # glTF stores linear RGB: compare with the sRGB colours given, converted.
    expected = sorted(tuple(round(Quantity_Color.Convert_sRGB_To_LinearRGB_s(c), 3) for c in (0.1 * i, 0.5, 0.9)) for i in range(6))
    assert len(colours) == len(expected)
    for got, want in zip(colours, expected):
        assert got == pytest.approx(want, abs=2e-3)
    triangles = sum(p["indices"] is not None for m in gltf["meshes"] for p in m["primitives"])
    assert triangles >= 6


def test_preview_in_a_missing_directory_is_write_failed(client, tmp_path):
    handle = client.load(box(), tmp_path)
    err = client.err("write_step", path=str(tmp_path / "a.step"), handle=handle, faces=[], preview=str(tmp_path / "no" / "a.glb"))
    assert err["code"] == "write_failed"
    assert not (tmp_path / "a.step").exists()
