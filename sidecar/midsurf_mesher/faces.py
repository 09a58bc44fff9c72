"""The named faces of a mid-surface STEP (OCP/XCAF): name, area, centroid and a normal per face, in the file's
face order. gmsh reads the same faces without their names; Rust matches the two lists by this geometry."""

import os

from OCP.BRepGProp import BRepGProp, BRepGProp_Face
from OCP.BRepTools import BRepTools
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Pnt, gp_Vec
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Reader
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name
from OCP.collections import Sequence_TDF_Label as TDF_LabelSequence
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS
from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool


def named_faces(path: str) -> dict:
    if not os.path.isfile(path):
        return {"error": f"{path}: no such file"}
    STEPCAFControl_Controller.Init_s()
    Interface_Static.SetIVal_s("read.stepcaf.subshapes.name", 1)
    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    XCAFApp_Application.GetApplication_s().InitDocument(doc)
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(path) != IFSelect_RetDone or not reader.Transfer(doc):
        return {"error": f"{path}: not a readable STEP file"}
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    roots = TDF_LabelSequence()
    tool.GetFreeShapes(roots)
    faces = []
    for r in range(1, roots.Length() + 1):
        root = roots.Value(r)
        fmap = TopTools_IndexedMapOfShape()
        TopExp.MapShapes_s(XCAFDoc_ShapeTool.GetShape_s(root), TopAbs_FACE, fmap)
        names = {}
        subs = TDF_LabelSequence()
        XCAFDoc_ShapeTool.GetSubShapes_s(root, subs)
        for i in range(1, subs.Length() + 1):
            label = subs.Value(i)
            # FindAttribute on a label without the attribute segfaults: ask IsAttribute first.
            if label.IsAttribute(TDataStd_Name.GetID_s()):
                name = TDataStd_Name()
                label.FindAttribute(TDataStd_Name.GetID_s(), name)
                names[fmap.FindIndex(XCAFDoc_ShapeTool.GetShape_s(label))] = name.Get().ToExtString()
        for i in range(1, fmap.Size() + 1):
            face = TopoDS.Face(fmap.FindKey(i))
            props = GProp_GProps()
            BRepGProp.SurfaceProperties_s(face, props)
            c = props.CentreOfMass()
            faces.append(
                {
                    "name": names.get(i, ""),
                    "area": props.Mass(),
                    "centroid": [c.X(), c.Y(), c.Z()],
                    **_point_normal(face),
                }
            )
    return {"faces": faces}


def _point_normal(face) -> dict:
    """A point at the centre of the face's UV box and the unit normal there, oriented as the face (BRepGProp_Face
    turns it over for a reversed face): Rust orients the elements by it."""
    umin, umax, vmin, vmax = BRepTools.UVBounds_s(face)
    p, n = gp_Pnt(), gp_Vec()
    BRepGProp_Face(face).Normal((umin + umax) / 2, (vmin + vmax) / 2, p, n)
    m = n.Magnitude()
    normal = [n.X() / m, n.Y() / m, n.Z() / m] if m > 0 else [0.0, 0.0, 0.0]
    return {"point": [p.X(), p.Y(), p.Z()], "normal": normal}
