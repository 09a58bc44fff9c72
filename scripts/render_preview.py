#!/usr/bin/env python3
"""Renders a midsurf preview (`--preview P.glb`) to a PNG, optionally over the edges of the input part, for the
documentation: no viewer or GPU needed, only numpy and Pillow from the pinned venv (and OCP for the outline).

    .venv/bin/python scripts/render_preview.py out/part.glb --outline part.step -o out/part.png

The mid-surface is drawn with flat shading in its faces' colours (the thickness bands of the STEP), back to front
(painter's algorithm, fine for an open surface seen from one side), the part's edges as thin grey lines on top.
"""

import argparse
import json
import struct
import sys

import numpy as np
from PIL import Image, ImageDraw

# glTF accessor component types and element sizes used by OCCT's writer.
COMPONENT = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
# Drawn at this multiple of the output size, then downsampled: cheap anti-aliasing.
SUPERSAMPLE = 3
# glTF primitive mode of a triangle list (the default when absent).
TRIANGLES = 4


def read_glb(path: str) -> list[tuple[np.ndarray, np.ndarray, tuple[float, float, float]]]:
    """(vertices n x 3, triangles m x 3, sRGB colour) per primitive, in the file's (Y-up) coordinates."""
    data = open(path, "rb").read()
    magic, _, _ = struct.unpack("<4sII", data[:12])
    if magic != b"glTF":
        sys.exit(f"render_preview: error: {path}: not a binary glTF file")
    json_length, _ = struct.unpack("<II", data[12:20])
    gltf = json.loads(data[20 : 20 + json_length])
    binary = data[20 + json_length + 8 :]

    def accessor(index: int) -> np.ndarray:
        acc = gltf["accessors"][index]
        view = gltf["bufferViews"][acc["bufferView"]]
        start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        width = WIDTH[acc["type"]]
        values = np.frombuffer(binary, COMPONENT[acc["componentType"]], acc["count"] * width, start)
        return values.reshape(-1, width) if width > 1 else values

    out = []
    for node in gltf["nodes"]:
        if "mesh" not in node:
            continue
        matrix = np.array(node.get("matrix", np.eye(4).flatten(order="F")), float).reshape(4, 4, order="F")
        for primitive in gltf["meshes"][node["mesh"]]["primitives"]:
            if primitive.get("mode", TRIANGLES) != TRIANGLES:
                continue  # OCCT writes a shape's free vertices as a point primitive: nothing to shade
            points = accessor(primitive["attributes"]["POSITION"]).astype(float)
            points = points @ matrix[:3, :3].T + matrix[:3, 3]
            triangles = accessor(primitive["indices"]).reshape(-1, 3)
            linear = gltf["materials"][primitive.get("material", 0)]["pbrMetallicRoughness"]["baseColorFactor"][:3]
            out.append((points, triangles, tuple(_srgb(c) for c in linear)))
    return out


def _srgb(linear: float) -> float:
    """glTF colour factors are linear; the picture is sRGB."""
    return 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055


def outline_edges(step_path: str) -> list[np.ndarray]:
    """Polylines of the part's edges, in the preview's coordinates (metres, Y-up, as OCCT's glTF writer puts
    them: (x, y, z) mm Z-up becomes (x, z, -y) / 1000)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GCPnts import GCPnts_QuasiUniformDeflection
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    from OCP.IFSelect import IFSelect_RetDone

    reader = STEPControl_Reader()
    if reader.ReadFile(step_path) != IFSelect_RetDone:
        sys.exit(f"render_preview: error: {step_path}: not a readable STEP file")
    reader.TransferRoots()
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_EDGE)
    lines = []
    while explorer.More():
        curve = BRepAdaptor_Curve(TopoDS.Edge(explorer.Current()))
        explorer.Next()
        sampled = GCPnts_QuasiUniformDeflection(curve, 0.02)
        if not sampled.IsDone() or sampled.NbPoints() < 2:
            continue
        points = [sampled.Value(k) for k in range(1, sampled.NbPoints() + 1)]
        lines.append(np.array([(p.X(), p.Z(), -p.Y()) for p in points]) / 1000.0)
    return lines


def view_matrix(azimuth: float, elevation: float) -> np.ndarray:
    """Rows: screen right, screen up, towards the viewer; Y is up in the scene."""
    a, e = np.radians(azimuth), np.radians(elevation)
    towards = np.array([np.cos(e) * np.sin(a), np.sin(e), np.cos(e) * np.cos(a)])
    right = np.cross([0.0, 1.0, 0.0], towards)
    right /= np.linalg.norm(right)
    return np.array([right, np.cross(towards, right), towards])


def render(meshes, lines, size: tuple[int, int], azimuth: float, elevation: float) -> Image.Image:
    view = view_matrix(azimuth, elevation)
    every = np.vstack([m[0] for m in meshes] + lines)
    low, high = (every @ view[:2].T).min(0), (every @ view[:2].T).max(0)
    width, height = size[0] * SUPERSAMPLE, size[1] * SUPERSAMPLE
    scale = 0.9 * min(width / (high[0] - low[0]), height / (high[1] - low[1]))
    centre = (low + high) / 2

    def screen(points: np.ndarray) -> np.ndarray:
        xy = (points @ view[:2].T - centre) * scale
        return np.column_stack([width / 2 + xy[:, 0], height / 2 - xy[:, 1]])

    light = np.array([0.3, 0.5, 1.0]) @ view  # from over the viewer's shoulder, in scene coordinates
    light /= np.linalg.norm(light)
    faces = []
    for points, triangles, colour in meshes:
        corners = points[triangles]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        lengths = np.linalg.norm(normals, axis=1)
        keep = lengths > 0
        shade = 0.5 + 0.5 * np.abs((normals[keep] / lengths[keep, None]) @ light)  # double-sided
        depth = (corners[keep].mean(1) @ view[2])
        for tri, s, d in zip(corners[keep], shade, depth):
            faces.append((d, screen(tri), tuple(int(255 * min(1.0, c * s)) for c in colour)))
    image = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(image)
    for _, tri, colour in sorted(faces, key=lambda f: f[0]):
        draw.polygon([tuple(p) for p in tri], fill=colour, outline=colour)
    for line in lines:
        draw.line([tuple(p) for p in screen(line)], fill=(110, 110, 110), width=SUPERSAMPLE)
    return image.resize(size, Image.LANCZOS)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("glb", help="the preview written by `midsurf run --preview`")
    parser.add_argument("--outline", metavar="PART.step", help="draw this part's edges over the mid-surface")
    parser.add_argument("-o", "--output", required=True, help="the PNG to write")
    parser.add_argument("--size", default="900x600", help="WIDTHxHEIGHT in pixels (default 900x600)")
    parser.add_argument("--azimuth", type=float, default=25.0, help="degrees about the up axis (default 25)")
    parser.add_argument("--elevation", type=float, default=35.0, help="degrees above the horizon (default 35)")
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    try:
        lines = outline_edges(args.outline) if args.outline else []
        render(read_glb(args.glb), lines, size, args.azimuth, args.elevation).save(args.output, optimize=True)
    except OSError as exc:
        sys.exit(f"render_preview: error: {exc.filename}: {exc.strerror}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
