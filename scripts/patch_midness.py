"""Per-face mid-ness of a midsurf output against its input, to find which patches the judge dislikes.

Run with the judge's Python (it imports ../shared/eval/midsurf_eval.py):
  ~/.cache/midsurf-judge/venv/bin/python scripts/patch_midness.py IN.step OUT.step
Prints, worst first: output face index, its name (patch id, thickness), area, median |d_up-d_down|/t,
median measured thickness.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "shared", "eval"))
import midsurf_eval as ev  # noqa: E402
from OCP.collections import Sequence_TDF_Label  # noqa: E402
from OCP.IFSelect import IFSelect_RetDone  # noqa: E402
from OCP.Interface import Interface_Static  # noqa: E402
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Reader  # noqa: E402
from OCP.TCollection import TCollection_ExtendedString  # noqa: E402
from OCP.TDataStd import TDataStd_Name  # noqa: E402
from OCP.TDocStd import TDocStd_Document  # noqa: E402
from OCP.TopAbs import TopAbs_FACE  # noqa: E402
from OCP.XCAFApp import XCAFApp_Application  # noqa: E402
from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool  # noqa: E402


def face_names(path):
    """Face index (MapShapes order of the file's one root shape) -> name."""
    STEPCAFControl_Controller.Init_s()
    Interface_Static.SetIVal_s("read.stepcaf.subshapes.name", 1)
    doc = TDocStd_Document(TCollection_ExtendedString("MDTV-XCAF"))
    XCAFApp_Application.GetApplication_s().InitDocument(doc)
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(path) != IFSelect_RetDone or not reader.Transfer(doc):
        return {}
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    roots = Sequence_TDF_Label()
    tool.GetFreeShapes(roots)
    names = {}
    for r in range(1, roots.Length() + 1):
        root = roots.Value(r)
        fmap = ev.ShapeMap()
        ev.TopExp.MapShapes_s(XCAFDoc_ShapeTool.GetShape_s(root), TopAbs_FACE, fmap)
        subs = Sequence_TDF_Label()
        XCAFDoc_ShapeTool.GetSubShapes_s(root, subs)
        for i in range(1, subs.Length() + 1):
            label = subs.Value(i)
            # FindAttribute on a label without the attribute segfaults: ask IsAttribute first.
            if label.IsAttribute(TDataStd_Name.GetID_s()):
                name = TDataStd_Name()
                label.FindAttribute(TDataStd_Name.GetID_s(), name)
                names[fmap.FindIndex(XCAFDoc_ShapeTool.GetShape_s(label)) - 1] = name.Get().ToExtString()
    return names


def explorer_names(shape, names):
    """`names` (MapShapes index -> name) re-keyed by TopExp_Explorer order, the order ev.tessellate numbers faces
    in. The two differ when the reader puts one face into several shells (it splits a non-manifold shell so)."""
    fmap = ev.ShapeMap()
    ev.TopExp.MapShapes_s(shape, TopAbs_FACE, fmap)
    explorer = ev.TopExp_Explorer(shape, TopAbs_FACE)
    keyed, k = {}, 0
    while explorer.More():
        m = fmap.FindIndex(explorer.Current()) - 1
        if m in names:
            keyed[k] = names[m]
        k += 1
        explorer.Next()
    return keyed


def main(inp, out):
    solid, mid = ev.read_step(inp), ev.read_step(out)
    d = ev.diag(solid)
    Vi, Fi, _ = ev.tessellate(solid, d * 2e-4)
    tm = ev.trimesh.Trimesh(Vi, Fi, process=False)
    ray = ev.trimesh.ray.ray_pyembree.RayMeshIntersector(tm) if ev.trimesh.ray.has_embree else tm.ray
    Vo, Fo, fo = ev.tessellate(mid, d * 2e-4)
    rng = np.random.default_rng(1)
    P, N, tidx = ev.sample_surface(Vo, Fo, 8000, rng)
    eps = d * 1e-6
    up = ev.first_hit(ray, P + N * eps, N)
    dn = ev.first_hit(ray, P - N * eps, -N)
    ok = np.isfinite(up) & np.isfinite(dn)
    asym = np.abs(up - dn) / np.where(ok, up + dn, 1)
    tri = Vo[Fo]
    area = np.bincount(fo, weights=0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1))
    names = explorer_names(mid, face_names(out))
    rows = []
    for f in np.unique(fo):
        m = (fo[tidx] == f) & ok
        if m.sum() < 3:
            continue
        rows.append((float(np.median(asym[m])), int(f), names.get(int(f), "?"), float(area[f]), float(np.median((up + dn)[m]))))
    rows.sort(reverse=True)
    # Share of the output area whose named thickness agrees with the measured one within 2%.
    agree = total = 0.0
    for _, f, name, a, t in rows:
        if " t=" in name:
            named = float(name.split(" t=")[1])
            total += a
            agree += a if abs(t - named) <= 0.02 * named else 0.0
    print(f"faces: thickness within 2% of the measured median: {agree / total * 100 if total else 0:.1f}% of the named area")
    # The same per patch (all samples of a patch's faces): what the report's thickness per patch claims.
    patch_of = {f: name.split(" t=")[0] for f, name in names.items() if " t=" in name}
    named_t = {name.split(" t=")[0]: float(name.split(" t=")[1]) for name in names.values() if " t=" in name}
    sample_patch = np.array([patch_of.get(int(f), "") for f in fo[tidx]])
    agree = total = 0.0
    patches_ok = patches = 0
    misses = []
    for patch, named in named_t.items():
        m = (sample_patch == patch) & ok
        if m.sum() < 3:
            continue
        a = sum(area[f] for f, p in patch_of.items() if p == patch)
        measured = float(np.median((up + dn)[m]))
        good = abs(measured - named) <= 0.02 * named
        if not good:
            misses.append((a, patch, named, measured))
        total += a
        agree += a if good else 0.0
        patches += 1
        patches_ok += good
    print(f"patches: median measured thickness within 2% of the reported one: {patches_ok}/{patches} patches, "
          f"{agree / total * 100 if total else 0:.1f}% of the named area")
    for a, patch, named, measured in sorted(misses, reverse=True):
        print(f"  miss {patch:<10} area {a:9.2f}  reported {named:.3f}  measured median {measured:.3f}")
    for r in rows[: int(sys.argv[3]) if len(sys.argv) > 3 else 25]:
        print(f"face {r[1]:4d}  {r[2]:<22} area {r[3]:10.2f}  mid {r[0]:.3f}  t_measured {r[4]:.3f}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
