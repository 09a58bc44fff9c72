"""The ops available after the handshake: each takes the handle store and the request's args and
returns the `ok` payload (see PROTOCOL.md). Importing this module imports OCP."""

import os
from collections.abc import Callable
from typing import Any

import OCP
from OCP.BRep import BRep_Builder
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Shape

from .constants import CONFUSION, RIM_SHARE
from .describe import face_graph, face_mesh
from .fuse import patch_fuse
from .geom import booleans
from .geom.topology import indexed_map, invalid_faces, surface_props, volume
from .joints import edge_probe, edge_strip
from .load import step_reader
from .patch import mid_patch
from .protocol.args import (
    as_number,
    as_point,
    handle_list,
    index_list,
    optional_bool,
    require_direction,
    require_handle,
    require_int,
    require_list,
    require_non_negative,
    require_number,
    require_object,
    require_point,
    require_positive,
    require_str,
)
from .protocol.errors import BadArgs, one_line
from .protocol.handles import HandleStore
from .write import bspline, readback, shells, step_writer

Op = Callable[[HandleStore, dict[str, Any]], dict[str, Any]]


def occt_version() -> str:
    # OCP versions are the OCCT version plus one build number (8.0.1.1 wraps OCCT 8.0.1).
    return ".".join(OCP.__version__.split(".")[:3])


def ping(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    return {"pong": True}


def load_step(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    solids, problems = step_reader.load_step_checked(require_str(args, "path"))
    measured = [(s, indexed_map(s, TopAbs_FACE).Size(), volume(s), surface_props(s).Mass()) for s in solids]
    # Handles only once everything is measured, so a failure leaves no orphan handles behind.
    solids_json = [{"handle": store.put(s), "faces": n, "volume": v, "area": a} for s, n, v, a in measured]
    return {"solids": solids_json, "entity_problems": problems}


def describe(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    shape = store.get(require_handle(args))
    mesh_tolerance = require_positive(args, "mesh_tolerance") if optional_bool(args, "mesh", False) else None
    return face_graph.describe(shape, mesh_tolerance)


def mesh(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    return face_mesh.face_meshes(store.get(require_handle(args)), require_positive(args, "mesh_tolerance"))


def make_patch(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    solid = store.get(require_handle(args))
    face_map = indexed_map(solid, TopAbs_FACE)
    count = face_map.Size()
    face_ids = index_list(args.get("faces"), count, "face", "the solid")
    if not face_ids:
        raise BadArgs("`faces` must list at least one face")
    if ("offset" in args) == ("plane" in args):
        raise BadArgs("make_patch needs exactly one of `offset` (mm) and `plane` ({origin, normal})")
    clip = _clip(args, count, len(face_ids))
    reverse = optional_bool(args, "reverse", False)
    offset = require_number(args, "offset") if "offset" in args else None
    # An offset to mid-wall is half the wall: a curved patch's overshoot of its rim within the rim tolerance
    # (a tenth of the wall) is left as it is (within_solid).
    negligible = RIM_SHARE * 2.0 * abs(offset) if offset is not None else 0.0
    # A patch on a skin (position top or bottom: a step to mid-wall) lies on the solid's boundary, not in it.
    on_skin = clip is not None and abs(clip.to_mid) > CONFUSION
    cut_planes = offset is not None and not on_skin
    options = mid_patch.Options(clip, reverse, _fill_edges(solid, args), solid, negligible, cut_planes)
    if offset is not None and optional_bool(args, "mid_wall", False):
        patch, faces, filled = mid_patch.mid_wall_patch(face_map, face_ids, offset, options)
    elif offset is not None:
        patch, faces, filled = mid_patch.offset_patch(face_map, face_ids, offset, options)
    else:
        plane = require_object(args, "plane")
        origin, normal = require_point(plane, "origin"), require_direction(plane, "normal")
        patch, faces, filled = mid_patch.projected_patch(face_map, face_ids, origin, normal, options)
    return {"handle": store.put(patch), "faces": faces, "filled": filled}


def _fill_edges(solid: TopoDS_Shape, args: dict[str, Any]) -> list[TopoDS_Shape]:
    """The optional `fill`: edge ids of the solid, as edges (the solid's edges are indexed only when asked)."""
    if "fill" not in args:
        return []
    edges = indexed_map(solid, TopAbs_EDGE)
    return [edges.FindKey(e + 1) for e in index_list(args["fill"], edges.Size(), "fill edge", "the solid")]


def _clip(args: dict[str, Any], count: int, faces: int) -> mid_patch.Clip | None:
    """The optional `clip`: {partners: [[face id]] per requested face, fuzzy, narrow, narrow_end (optional,
    defaults to narrow), exclude (optional: [[face id]] per requested face), thickness, to_mid and wall_max
    (optional, together: the wall's thickness, the step from the patch to mid-wall along the faces' outward
    normals, the thickest wall that pairs whatever its width)}."""
    if "clip" not in args:
        return None
    clip = require_object(args, "clip")
    partners = require_list(clip, "partners")
    if len(partners) != faces:
        raise BadArgs(f"clip.partners has {len(partners)} lists for {faces} faces: give one list per face")
    narrow = require_non_negative(clip, "narrow")
    exclude = require_list(clip, "exclude") if "exclude" in clip else [[] for _ in partners]
    if len(exclude) != faces:
        raise BadArgs(f"clip.exclude has {len(exclude)} lists for {faces} faces: give one list per face")
    return mid_patch.Clip(
        [index_list(p, count, "partner face", "the solid") for p in partners],
        require_non_negative(clip, "fuzzy"),
        narrow,
        require_non_negative(clip, "narrow_end") if "narrow_end" in clip else narrow,
        [index_list(e, count, "excluded face", "the solid") for e in exclude],
        *_clip_wall(clip),
    )


def _clip_wall(clip: dict[str, Any]) -> tuple[float | None, float, float]:
    """The clip's optional wall: (thickness, to_mid, wall_max), all three given or none."""
    keys = ("thickness", "to_mid", "wall_max")
    given = [k in clip for k in keys]
    if not any(given):
        return None, 0.0, 0.0
    if not all(given):
        raise BadArgs("clip needs all of `thickness`, `to_mid` and `wall_max`, or none")
    return require_positive(clip, "thickness"), require_number(clip, "to_mid"), require_positive(clip, "wall_max")


def fuse(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    handles = handle_list(args, "patches")
    repeated = sorted({h for h in handles if handles.count(h) > 1})
    if repeated:
        raise BadArgs(f"patch handles {repeated} are listed more than once")
    fuzzy = require_non_negative(args, "fuzzy")
    split_internal = optional_bool(args, "split_internal", False)
    bodies = args.get("bodies")
    if bodies is not None and (
        not isinstance(bodies, list)
        or len(bodies) != len(handles)
        or not all(isinstance(b, int) and not isinstance(b, bool) and b >= 0 for b in bodies)
    ):
        raise BadArgs(f"`bodies` must list a body number (integer >= 0) per patch, got {bodies!r}")
    patches_fused = optional_bool(args, "patches_fused", False)
    settled = set(index_list(args.get("settled", []), len(handles), "patch", "`patches`"))
    shapes = [store.get(h) for h in handles]
    fused, described = patch_fuse.fuse(shapes, fuzzy, split_internal, bodies, patches_fused, settled)
    if split_internal:
        # A stitching pass's result: the faces that fail BRepCheck, which the write would leave out.
        described["invalid"] = invalid_faces(fused, indexed_map(fused, TopAbs_FACE)) or []
    return {"handle": store.put(fused), **described}


def make_shells(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    face_map = indexed_map(store.get(require_handle(args)), TopAbs_FACE)
    groups = require_list(args, "shells")
    used: dict[int, int] = {}
    for j, group in enumerate(groups):
        for face_id in index_list(group, face_map.Size(), "face", "the fused shape"):
            if face_id in used:
                raise BadArgs(f"face {face_id} is in shells {used[face_id]} and {j}: one shell per face")
            used[face_id] = j
        if not group:
            raise BadArgs(f"shell {j} is empty: list at least one face per shell")
    merge = args.get("merge", [])
    if not isinstance(merge, list):
        raise BadArgs(f"`merge` must be a list of face lists, got {merge!r}")
    for j, group in enumerate(merge):
        faces = index_list(group, face_map.Size(), "face", "the fused shape")
        if len(faces) < 2 or any(f not in used for f in faces) or len({used[f] for f in faces}) != 1:
            raise BadArgs(f"merge set {j} must list two or more faces of one shell, got {group!r}")
    compound, described = shells.make_shells(face_map, groups, require_non_negative(args, "fuzzy"), merge)
    return {"handle": store.put(compound), **described}


def write_step(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    path = require_str(args, "path")
    shape = store.get(require_handle(args))
    faces = [_face_attributes(entry) for entry in require_list(args, "faces")]
    preview = args.get("preview")
    if preview is not None and not isinstance(preview, str):
        raise BadArgs(f"`preview` must be a path string, got {preview!r}")
    kept = args.get("solids", [])
    if not isinstance(kept, list):
        raise BadArgs(f"`solids` must be a list, got {kept!r}")
    solids = [_kept_solid(store, entry) for entry in kept]
    check = args.get("check", False)
    if not isinstance(check, bool):
        raise BadArgs(f"`check` must be true or false, got {check!r}")
    written = {"path": path, "bytes": step_writer.write_step(path, shape, faces, preview, solids)}
    if not check:
        return written
    checked = readback.check_written(path, shape)
    if checked.dropped and (checked.unnamed or bspline.any_offset_surface(shape, checked.invalid)):
        # The reader dropped faces: most often offset surfaces (freeform mid-patches) it cannot rebuild. The
        # same shape with B-spline surfaces fitted to them replaces the file when it reads back better (not
        # tried when no face named broken is one: fitted surfaces are heavy to write and read).
        fitted = bspline.without_offset_surfaces(shape)
        if fitted is not shape:
            trial = path + ".bspline"
            # The preview already written shows the same surfaces.
            size = step_writer.write_step(trial, fitted, faces, None, solids)
            again = readback.check_written(trial, fitted)
            if _broken(again) < _broken(checked):
                os.replace(trial, path)
                written["bytes"], checked = size, again
            else:
                os.remove(trial)
    written["valid"], written["invalid"] = checked.valid, checked.invalid
    written["max_edge_tolerance"] = checked.max_edge_tolerance
    written["free_edges"] = checked.free_edges
    return written


def _broken(checked: readback.Check) -> int:
    """Faces a reader breaks or drops (an invalid file with none named counts as one)."""
    return 0 if checked.valid else max(len(checked.invalid), checked.dropped, 1)


def _kept_solid(store: HandleStore, entry: Any) -> tuple[str, TopoDS_Shape]:
    """A solid written as it is beside the mid-surface: (name, shape)."""
    if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
        raise BadArgs(f"each of `solids` must be an object with a handle and a name, got {entry!r}")
    return entry["name"], store.get(require_handle(entry))


def _face_attributes(entry: Any) -> step_writer.FaceAttributes:
    if not isinstance(entry, dict):
        raise BadArgs(f"each of `faces` must be an object, got {entry!r}")
    name = entry.get("name")
    if name is not None and not isinstance(name, str):
        raise BadArgs(f"face name must be a string, got {name!r}")
    color = entry.get("color")
    if color is not None:
        if not isinstance(color, list) or len(color) != 3:
            raise BadArgs(f"face color must be [r, g, b], got {color!r}")
        color = tuple(as_number(c, "a color component") for c in color)
        if not all(0.0 <= c <= 1.0 for c in color):
            raise BadArgs(f"color components must be within 0..1, got {list(color)}")
    thickness = entry.get("thickness")
    if thickness is not None:
        thickness = as_number(thickness, "face thickness")
    return step_writer.FaceAttributes(require_int(entry, "face"), name, color, thickness)


def probe_edges(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    shape = store.get(require_handle(args))
    face_map, edge_map = indexed_map(shape, TopAbs_FACE), indexed_map(shape, TopAbs_EDGE)
    samples = require_int(args, "samples", 2)
    reach = require_positive(args, "reach")
    targets = index_list(args.get("targets"), face_map.Size(), "target face", "the fused shape")
    edges = []
    for entry in require_list(args, "edges"):
        if not isinstance(entry, dict):
            raise BadArgs(f"each of `edges` must be an object, got {entry!r}")
        (face_id,) = index_list([require_int(entry, "face")], face_map.Size(), "face", "the fused shape")
        (edge_id,) = index_list([require_int(entry, "edge")], edge_map.Size(), "edge", "the fused shape")
        edges.append((TopoDS.Face(face_map.FindKey(face_id + 1)), edge_map.FindKey(edge_id + 1), face_id))
    faces = edge_probe.TargetFaces({i: TopoDS.Face(face_map.FindKey(i + 1)) for i in targets}, reach)
    return {"edges": edge_probe.probe(edges, faces, samples, reach)}


def extend_edges(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    shape = store.get(require_handle(args))
    face_map, edge_map = indexed_map(shape, TopAbs_FACE), indexed_map(shape, TopAbs_EDGE)
    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    made_json: list[dict[str, Any]] = []
    for j, entry in enumerate(require_list(args, "strips")):
        if not isinstance(entry, dict):
            raise BadArgs(f"each of `strips` must be an object, got {entry!r}")
        (face_id,) = index_list([require_int(entry, "face")], face_map.Size(), "face", "the fused shape")
        (edge_id,) = index_list([require_int(entry, "edge")], edge_map.Size(), "edge", "the fused shape")
        lengths = [as_number(v, "a strip length") for v in require_list(entry, "lengths")]
        along = as_point(entry["along"], f"strip {j}'s along") if "along" in entry else None
        # Swept `along`, lengths of 0 make an upright band.
        if len(lengths) < 2 or min(lengths) < 0.0 or (along is None and min(lengths) == 0.0):
            raise BadArgs(f"strip {j}: at least 2 lengths, all positive (or 0 with `along`), got {lengths}")
        onto_face = optional_bool(entry, "onto_face", False)
        face = TopoDS.Face(face_map.FindKey(face_id + 1))
        # One strip the kernel cannot make is that joint's failure, not the whole request's.
        try:
            made = edge_strip.strip(face, edge_map.FindKey(edge_id + 1), lengths, onto_face, along)
        except Exception as exc:  # OCCT raises its own Standard_Failure types
            made_json.append({"area": None, "error": one_line(exc)})
            continue
        builder.Add(compound, made)
        made_json.append({"area": surface_props(made).Mass(), "error": None})
    corners_json: list[dict[str, Any]] = []
    for j, entry in enumerate(args.get("corners", [])):
        if not isinstance(entry, dict) or not isinstance(entry.get("points"), list) or len(entry["points"]) != 4:
            raise BadArgs(f"corner {j} must be {{points: [4 points], normal}}, got {entry!r}")
        points = [as_point(p, f"corner {j}'s points") for p in entry["points"]]
        normal = require_direction(entry, "normal")
        axis = _corner_axis(entry, j)
        try:
            made = edge_strip.corner(points, normal, axis)
        except Exception as exc:  # OCCT raises its own Standard_Failure types
            corners_json.append({"area": None, "error": one_line(exc)})
            continue
        builder.Add(compound, made)
        corners_json.append({"area": surface_props(made).Mass(), "error": None})
    return {"handle": store.put(compound), "strips": made_json, "corners": corners_json}


def _corner_axis(entry: dict[str, Any], j: int) -> tuple[tuple[float, float, float], tuple[float, float, float]] | None:
    """A corner's optional `axis`: [a point on it, its direction] (normalised)."""
    if "axis" not in entry:
        return None
    axis = entry["axis"]
    if not isinstance(axis, list) or len(axis) != 2:
        raise BadArgs(f"corner {j}'s axis must be [point, direction], got {axis!r}")
    return as_point(axis[0], f"corner {j}'s axis point"), require_direction({"direction": axis[1]}, "direction")


def gather(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    """A compound of chosen faces of several shapes (one patch's kept pieces and its strips)."""
    faces = []
    for entry in require_list(args, "parts"):
        if not isinstance(entry, dict):
            raise BadArgs(f"each of `parts` must be an object, got {entry!r}")
        face_map = indexed_map(store.get(require_handle(entry)), TopAbs_FACE)
        for face_id in index_list(entry.get("faces"), face_map.Size(), "face", "the shape"):
            faces.append(face_map.FindKey(face_id + 1))
    if not faces:
        raise BadArgs("gather needs at least one face")
    unify = args.get("unify")
    if unify is not None and len(faces) > 1:
        shape = booleans.unify(faces, as_number(unify, "the unify tolerance"))
    else:
        builder, shape = BRep_Builder(), TopoDS_Compound()
        builder.MakeCompound(shape)
        for face in faces:
            builder.Add(shape, face)
    return {"handle": store.put(shape), "faces": indexed_map(shape, TopAbs_FACE).Size()}


def free(store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    return {"freed": store.free(handle_list(args))}


OPS: dict[str, Op] = {
    "ping": ping,
    "load_step": load_step,
    "describe": describe,
    "mesh": mesh,
    "make_patch": make_patch,
    "fuse": fuse,
    "make_shells": make_shells,
    "write_step": write_step,
    "probe_edges": probe_edges,
    "extend_edges": extend_edges,
    "gather": gather,
    "free": free,
}
