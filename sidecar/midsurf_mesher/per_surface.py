"""The fallback when the whole model does not mesh: each surface left is meshed on its own, in a child with a
time limit, trying in turn: alone in the model (the boundary mesh shared with its neighbours, so conforming)
with frontal-Delaunay, then MeshAdapt; then healed alone (OCCT's ShapeFix on the face: "Impossible to mesh
periodic surface" and "1D mesh not forming a closed loop" come from small or degenerate edges it removes),
with the same two. A healed face's edges that ShapeFix left as they were mesh to the same nodes as its
neighbours' and are merged with them; the others leave a gap, which the quality report's free edges show.
A surface none of these meshes is named in `unmeshed`.

Pieces (the whole model's, then each surface's) are merged: nodes on CAD vertices and curves by position
(rounded to POSITION_SHARE of the model's extent), a surface's inside nodes per piece."""

import gmsh

from .child import in_child
from .collect import collect

# Nodes on vertices and curves closer than this share of the model's extent are one node: the same curve meshed
# in two children gives bit-identical nodes, a healed copy of it nodes within about 1e-9 of the extent.
POSITION_SHARE = 1e-7
# ShapeFix's tolerance on the healed face (mm): OCCT's confusion tolerance is 1e-7.
HEAL_TOLERANCE = 1e-6
FRONTAL_DELAUNAY, MESH_ADAPT = 6, 1


def mesh_each(surfaces: list[dict], todo: list[int], done: list[dict], limits, fault) -> dict:
    """Meshes the surfaces `todo` one by one; `done` holds the pieces already meshed. Returns the merged mesh
    with `retried` and `unmeshed`."""
    gmsh.model.mesh.generate(1)
    area = {s["tag"]: s["area"] for s in surfaces}
    pieces, retried, unmeshed = list(done), [], []
    for tag in todo:
        why = "no elements"
        for how, attempt in _attempts(tag, fault):
            outcome = in_child(attempt, limits.surface(area[tag]))
            if outcome.failure:
                why = f"{how}: {outcome.failure}"
                continue
            if any(b["quads"] or b["trias"] for b in outcome.value["elements"]):
                pieces.append(outcome.value)
                retried.append({"surface": tag, "how": how})
                break
            why = f"{how}: no elements"
        else:
            unmeshed.append({"surface": tag, "why": why})
    return {**merge(pieces), "retried": retried, "unmeshed": unmeshed}


def _attempts(tag: int, fault):
    for name, algorithm in (("frontal-Delaunay", FRONTAL_DELAUNAY), ("MeshAdapt", MESH_ADAPT)):
        yield f"alone, {name}", lambda a=algorithm: _alone(tag, a, fault)
    for name, algorithm in (("frontal-Delaunay", FRONTAL_DELAUNAY), ("MeshAdapt", MESH_ADAPT)):
        yield f"healed, {name}", lambda a=algorithm: _healed(tag, a, fault)


def _alone(tag: int, algorithm: int, fault) -> dict:
    """Runs in a child: surface `tag` alone, on the boundary mesh the parent made."""
    if fault.strikes(tag):
        return {"nodes": [], "node_dims": [], "elements": []}
    gmsh.option.setNumber("Mesh.MeshOnlyVisible", 1)
    gmsh.model.setVisibility(gmsh.model.getEntities(2), 0)
    gmsh.model.setVisibility([(2, tag)], 1, recursive=True)
    gmsh.model.mesh.setAlgorithm(2, tag, algorithm)
    gmsh.model.mesh.generate(2)
    return collect([tag])


def _healed(tag: int, algorithm: int, fault) -> dict:
    """Runs in a child: surface `tag` healed in a model of its own."""
    if fault.strikes(tag):
        return {"nodes": [], "node_dims": [], "elements": []}
    gmsh.model.mesh.clear()
    others = [(2, t) for _, t in gmsh.model.getEntities(2) if t != tag]
    gmsh.model.occ.remove(others, recursive=True)
    gmsh.model.occ.healShapes(
        [(2, tag)], tolerance=HEAL_TOLERANCE, fixDegenerated=True, fixSmallEdges=True, fixSmallFaces=True,
        sewFaces=False, makeSolids=False,
    )
    gmsh.model.occ.synchronize()
    tags = [t for _, t in gmsh.model.getEntities(2)]
    for t in tags:
        gmsh.model.mesh.setAlgorithm(2, t, algorithm)
    gmsh.model.mesh.generate(2)
    return collect(tags, as_surface=tag)


def merge(pieces: list[dict]) -> dict:
    """One mesh of `pieces`, nodes in the order elements first use them (unused ones dropped)."""
    points = [p for piece in pieces for p in piece["nodes"]]
    extent = max((max(p[k] for p in points) - min(p[k] for p in points) for k in range(3)), default=0.0)
    table = _NodeTable(POSITION_SHARE * max(extent, 1e-9))
    elements = []
    for n, piece in enumerate(pieces):
        for block in piece["elements"]:
            quads = [[table.ref(piece, n, i) for i in q] for q in block["quads"]]
            trias = [[table.ref(piece, n, i) for i in t] for t in block["trias"]]
            if quads or trias:
                elements.append({"surface": block["surface"], "quads": quads, "trias": trias})
    return {"nodes": table.nodes, "node_dims": table.dims, "elements": elements}


class _NodeTable:
    """The merged nodes: one per rounded position on vertices and curves, one per piece's node inside."""

    def __init__(self, step: float):
        self.step, self.index, self.nodes, self.dims = step, {}, [], []

    def ref(self, piece: dict, n: int, i: int) -> int:
        p, dim = piece["nodes"][i], piece["node_dims"][i]
        key = ("edge", *(round(x / self.step) for x in p)) if dim < 2 else ("inside", n, i)
        if key not in self.index:
            self.index[key] = len(self.nodes)
            self.nodes.append(p)
            self.dims.append(dim)
        return self.index[key]
