"""The STEP file as any reader sees it: read back and checked, face by face.

A face that fails BRepCheck in memory is often repaired by the reader's healing (its pcurves, its tolerances);
one that still fails once read back is broken for every user of the file. The check names those faces by their
index in the written shape: the reader's order when it read as many faces as were written (manifold shells read
back as written), else the face with the same centroid and area.
"""

from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS_Shape

from ..constants import READBACK_MATCH
from ..geom.topology import indexed_map


def check_written(path: str, shape: TopoDS_Shape) -> tuple[bool, list[int]]:
    """(whether the file at `path` reads back valid, the faces of `shape` (MapShapes order) whose read-back
    face fails BRepCheck). A file that cannot be read back counts as invalid with no face named."""
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        return False, []
    reader.TransferRoots()
    back = reader.OneShape()
    if BRepCheck_Analyzer(back).IsValid():
        return True, []
    back_faces = []
    explorer = TopExp_Explorer(back, TopAbs_FACE)
    while explorer.More():
        back_faces.append(explorer.Current())
        explorer.Next()
    bad = [k for k, face in enumerate(back_faces) if not BRepCheck_Analyzer(face).IsValid()]
    own = indexed_map(shape, TopAbs_FACE)
    if len(back_faces) == own.Size():
        # Manifold shells read back as written, face for face in the same order; a broken face's area and
        # centroid cannot be trusted to find it.
        return False, bad
    written = [_centroid_and_area(own.FindKey(j + 1)) for j in range(own.Size())]
    size = max((max(abs(c) for c in centroid) for centroid, _ in written), default=1.0)
    invalid = set()
    for centroid, area in (_centroid_and_area(back_faces[k]) for k in bad):
        nearest = min(range(len(written)), key=lambda j: _distance(written[j][0], centroid), default=None)
        if nearest is None:
            continue
        near_centroid, near_area = written[nearest]
        close = _distance(near_centroid, centroid) <= READBACK_MATCH * max(size, 1.0)
        if close and abs(near_area - area) <= READBACK_MATCH * max(near_area, area) + 1e-12:
            invalid.add(nearest)
    return False, sorted(invalid)


def _centroid_and_area(face: TopoDS_Shape) -> tuple[tuple[float, float, float], float]:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face, props)
    c = props.CentreOfMass()
    return (c.X(), c.Y(), c.Z()), props.Mass()


def _distance(a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
    return sum((x - y) ** 2 for x, y in zip(a, b)) ** 0.5
