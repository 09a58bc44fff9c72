"""gmsh side of `midsurf mesh`: reads the mid-surface STEP with gmsh's own OCCT, meshes every surface with
shells, and returns per surface its geometry (for Rust's matching) and elements. The small-edge clean-up is
Rust's (mesh::cleanup): gmsh's own OCC healing (Geometry.OCCFixSmallEdges/Faces) was tried and dropped, as it
fails on real mid-surfaces ("Could not fix wire") and merges faces of different patches.

The whole model is meshed at once, in a child process with a time limit (child.py). When that fails, runs out
of time or leaves surfaces empty, the surfaces left are meshed one by one (per_surface.py) and a surface that
still cannot be meshed is named in `unmeshed`: the decks are written without it.

Request (JSON on stdin):
  {"path": STEP, "size": h, "all_quads": bool,
   "time_floor_s": s, "time_per_element_s": s, "expected_elements": n}   // time limits: see TimeLimits
Reply:
  {"gmsh": version,
   "surfaces": [{"tag": s, "area": A, "centroid": [..]}, ...],   // gmsh's order, every surface
   "nodes": [[x, y, z], ...], "node_dims": [0|1|2, ...],      // 0-based node index; dim of its CAD entity
   "elements": [{"surface": s, "quads": [[a,b,c,d], ...], "trias": [[a,b,c], ...]}, ...],
   "whole_model": "meshed" | why not, "retried": [{"surface": s, "how": ...}],
   "unmeshed": [{"surface": s, "why": ...}], "gmsh_errors": [first errors gmsh logged],
   "address_layout": "fixed" | "random"}   // __main__'s: "fixed" makes the mesh repeatable
Everything is single-threaded so that the same request gives the same mesh.
"""

from dataclasses import dataclass

import gmsh

from . import per_surface
from .child import in_child
from .collect import collect, empty_surfaces
from .faults import Fault

# gmsh's errors kept in the reply (the first ones: the rest repeat them for the next surfaces).
KEPT_ERRORS = 20


@dataclass
class TimeLimits:
    """How long an attempt may run before it counts as hung: a floor plus a time per expected element (Rust
    derives both; gmsh meshed the corpus at about 0.3 ms per element)."""

    floor_s: float
    per_element_s: float
    expected_elements: float
    size: float

    def whole(self) -> float:
        return self.floor_s + self.per_element_s * self.expected_elements

    def surface(self, area: float) -> float:
        # A surface's own estimate, at most the model's (a broken face can report an absurd area).
        elements = min(max(area, 0.0) / (self.size * self.size), self.expected_elements)
        return self.floor_s + self.per_element_s * elements


def mesh(request: dict) -> dict:
    path = request["path"]
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        return _mesh(request)
    except Exception as e:  # gmsh raises plain Exceptions carrying its last error
        return {"error": f"{path}: gmsh failed: {e}"}
    finally:
        gmsh.finalize()


def _mesh(request: dict) -> dict:
    size = float(request["size"])
    fault = Fault.from_env()
    limits = TimeLimits(
        float(request["time_floor_s"]), float(request["time_per_element_s"]), float(request["expected_elements"]), size
    )
    if fault.hangs:
        limits = TimeLimits(fault.time_limit_s, 0.0, 0.0, size)
    _set_options(size, bool(request.get("all_quads", False)))
    gmsh.model.occ.importShapes(request["path"])
    gmsh.model.occ.synchronize()
    surfaces = []
    for _, tag in gmsh.model.getEntities(2):
        c = gmsh.model.occ.getCenterOfMass(2, tag)
        surfaces.append({"tag": tag, "area": gmsh.model.occ.getMass(2, tag), "centroid": list(c)})

    whole = in_child(lambda: _whole_model(fault), limits.whole())
    reply = {"gmsh": gmsh.__version__, "surfaces": surfaces}
    if not whole.failure and not whole.value["empty"]:
        piece = whole.value
        return {**reply, **piece["mesh"], "whole_model": "meshed", "retried": [], "unmeshed": [],
                "gmsh_errors": piece["errors"]}
    if whole.failure:
        why, done, todo, errors = f"failed: {whole.failure}", [], [s["tag"] for s in surfaces], []
    else:
        todo, errors = whole.value["empty"], whole.value["errors"]
        why, done = f"left {len(todo)} surface(s) empty", [whole.value["mesh"]]
    merged = per_surface.mesh_each(surfaces, todo, done, limits, fault)
    return {**reply, **merged, "whole_model": why, "gmsh_errors": errors}


def _set_options(size: float, all_quads: bool) -> None:
    opt = gmsh.option.setNumber
    opt("General.Terminal", 0)
    opt("General.NumThreads", 1)
    opt("Mesh.MaxNumThreads2D", 1)
    # A surface that fails is left empty and the others are meshed (the default, 2, stops at the first error).
    opt("General.AbortOnError", 0)
    # Keep the shell's shared edges shared: no sewing that could re-split them, no scaling.
    opt("Geometry.OCCSewFaces", 0)
    opt("Mesh.MeshSizeMax", size)
    opt("Mesh.MeshSizeMin", 0)
    # Element size from the target only: not from curvature (it refines every small fillet) nor from the
    # CAD points' characteristic lengths.
    opt("Mesh.MeshSizeFromCurvature", 0)
    opt("Mesh.MeshSizeFromPoints", 0)
    opt("Mesh.MeshSizeExtendFromBoundary", 1)
    # Frontal-Delaunay, then recombined. Its quad variant (8) makes elements twice the size asked on cylinders
    # (pipe_tee fixture at 4 mm: 89 elements on a 6828 mm2 half pipe, 5% of the area lost to the chords).
    opt("Mesh.Algorithm", 6)
    opt("Mesh.RecombineAll", 1)
    opt("Mesh.RecombinationAlgorithm", 1)  # Blossom
    if all_quads:
        # Every triangle left by the recombination is split into 3 quads, every quad into 4: the mesh is
        # made at twice the size so that the split gives the target size.
        opt("Mesh.SubdivisionAlgorithm", 1)
        opt("Mesh.MeshSizeMax", 2 * size)


def _whole_model(fault: Fault) -> dict:
    """Runs in the child: every surface at once."""
    fault.strike_whole()
    gmsh.logger.start()
    gmsh.model.mesh.generate(2)
    errors = [m for m in gmsh.logger.get() if m.startswith("Error")][:KEPT_ERRORS]
    gmsh.logger.stop()
    tags = [tag for _, tag in gmsh.model.getEntities(2)]
    return {"mesh": collect(tags), "empty": empty_surfaces(tags), "errors": errors}
