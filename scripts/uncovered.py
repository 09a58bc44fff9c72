"""Where a midsurf output leaves the input's material uncovered, and why: the judge's coverage (interior points
farther than 0.75 x the named thickness from the mid-surface) split by the input face nearest to each uncovered
point, with that face's role from `midsurf pairs --json` (paired, connecting, unpaired and the test its nearest
candidate failed), then summed per role and failed test.

Run with the judge's Python (it imports ../shared/eval/midsurf_eval.py):
  ~/.cache/midsurf-judge/venv/bin/python scripts/uncovered.py IN.step OUT.step [--pairs PAIRS.json] [--samples N]
Without --pairs it runs `midsurf pairs --json IN.step` (MIDSURF_BIN, else target/release/midsurf). Faces are
numbered as `midsurf pairs` numbers them within each solid; the solids' faces follow one another in the file's
order, as the judge's tessellation visits them.
"""
import argparse
import json
import os
import subprocess
import sys
from collections import defaultdict

import igl
import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "..", "shared", "eval"))
import midsurf_eval as ev  # noqa: E402
from OCP.BRepGProp import BRepGProp  # noqa: E402
from OCP.GProp import GProp_GProps  # noqa: E402
from OCP.TopAbs import TopAbs_FACE  # noqa: E402


def roles_of(part, pairs_path):
    """(solid number, face index within it, role) per face of the part, in the judge's face order."""
    if pairs_path:
        with open(pairs_path) as f:
            pairs = json.load(f)
    else:
        binary = os.environ.get("MIDSURF_BIN", os.path.join(ROOT, "target", "release", "midsurf"))
        pairs = json.loads(subprocess.run([binary, "pairs", "--json", part], capture_output=True, check=True).stdout)
    solids = [(solid["pairing"]["roles"], solid["tolerances"]["t_max"]) for solid in pairs["solids"]]
    return [(s + 1, i, role, t_max) for s, (roles, t_max) in enumerate(solids) for i, role in enumerate(roles)]


def named_thickness(mid, path):
    """The thickness named on each output face (by the nearest named centroid, as the judge matches them)."""
    named = ev.named_faces(path)
    centres = np.array([c for c, _, _ in named])
    out = []
    explorer = ev.TopExp_Explorer(mid, TopAbs_FACE)
    while explorer.More():
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(explorer.Current(), props)
        c = props.CentreOfMass()
        nearest = int(np.argmin(np.linalg.norm(centres - np.array([c.X(), c.Y(), c.Z()]), axis=1)))
        out.append(named[nearest][2] or 0.0)
        explorer.Next()
    return np.array(out)


def interior_points(V, F, count, rng):
    lo, hi = V.min(0), V.max(0)
    points = []
    while len(points) < count:
        candidates = lo + rng.random((50000, 3)) * (hi - lo)
        inside = igl.fast_winding_number(V, F, candidates) > 0.5
        points.extend(candidates[inside][: count - len(points)])
    return np.array(points)


def role_key(role):
    rejection = (role.get("near_miss") or {}).get("rejection", {}).get("test")
    return role.get("role", "?") + (f" ({rejection})" if rejection else "")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("part")
    parser.add_argument("output")
    parser.add_argument("--pairs", help="`midsurf pairs --json` of the part (run when not given)")
    parser.add_argument("--samples", type=int, default=20000)
    parser.add_argument("--top", type=int, default=20, help="faces listed, most uncovered first")
    args = parser.parse_args()

    part, mid = ev.read_step(args.part), ev.read_step(args.output)
    d = ev.diag(part)
    Vi, Fi, face_in = ev.tessellate(part, d * 2e-4)
    Vo, Fo, face_out = ev.tessellate(mid, d * 2e-4)
    t_out = named_thickness(mid, args.output)
    points = interior_points(Vi, Fi, args.samples, np.random.default_rng(1))
    squared, triangle, _ = igl.point_mesh_squared_distance(points, Vo, Fo)
    uncovered = np.sqrt(squared) > 0.75 * t_out[face_out[triangle]]
    print(f"coverage {1 - uncovered.mean():.3f} ({args.samples} interior points; the judge counts thin solids only)")

    _, nearest_triangle, _ = igl.point_mesh_squared_distance(points[uncovered], Vi, Fi)
    nearest = face_in[nearest_triangle]
    chord, far = material_chord(Vi, Fi, face_in, points[uncovered], nearest_triangle)
    roles = roles_of(args.part, args.pairs)
    faces, counts = np.unique(nearest, return_counts=True)
    by_role = defaultdict(float)
    t_max = np.array([roles[f][3] if f < len(roles) else np.inf for f in nearest])
    print(f"{'share':>6}  solid face  role (failed test of the nearest candidate)  chord  far  centre of its uncovered points")
    for rank, k in enumerate(np.argsort(-counts)):
        face, share = int(faces[k]), counts[k] / args.samples
        solid, index, role, _ = roles[face] if face < len(roles) else (0, face, {}, np.inf)
        by_role[role_key(role)] += share
        if rank < args.top:
            mine = nearest == face
            centre = np.round(points[uncovered][mine].mean(0), 1)
            far_faces = far[mine][far[mine] >= 0]
            far_face = roles[int(np.bincount(far_faces).argmax())][1] if len(far_faces) else -1
            print(f"{share:6.3f}  {solid:5d} {index:4d}  {role_key(role):42s}  {np.median(chord[mine]):5.2f} {far_face:4d}  {centre}")
    print("by role:", ", ".join(f"{key} {share:.3f}" for key, share in sorted(by_role.items(), key=lambda x: -x[1])))
    ratio = chord / t_max
    bands = [(0, 1, "chord <= t_max"), (1, 2, "t_max-2x"), (2, 4, "2x-4x"), (4, np.inf, "> 4x t_max or open")]
    print("by material chord along the nearest face's normal:",
          ", ".join(f"{name} {((ratio > lo) & (ratio <= hi)).sum() / args.samples:.3f}" for lo, hi, name in bands))


def material_chord(V, F, face_of, points, triangle):
    """The material's thickness through each point along the normal of its nearest input triangle (the sum of
    the first hits both ways), and the input face hit on the far side of the nearest face (-1 where none)."""
    import trimesh

    mesh = trimesh.Trimesh(V, F, process=False)
    ray = trimesh.ray.ray_pyembree.RayMeshIntersector(mesh) if trimesh.ray.has_embree else mesh.ray
    normals = mesh.face_normals[triangle]
    out, _ = first_hits(ray, points, normals, face_of)
    back, far = first_hits(ray, points, -normals, face_of)
    return out + back, far


def first_hits(ray, origins, dirs, face_of):
    """Distance to the first hit along each ray (inf where none), as the judge's first_hit measures it, and the
    input face hit there (-1 where none)."""
    locations, index, hit = ray.intersects_location(origins, dirs, multiple_hits=False)
    distance = np.full(len(origins), np.inf)
    face = np.full(len(origins), -1)
    lengths = np.linalg.norm(locations - origins[index], axis=1) if len(index) else np.zeros(0)
    for k in np.argsort(-lengths):  # nearest last: it is the one kept
        distance[index[k]] = lengths[k]
        face[index[k]] = face_of[hit[k]]
    return distance, face

if __name__ == "__main__":
    main()
