"""Renders a `midsurf mesh` Abaqus deck (.inp) or preview (.glb) to a PNG: shells coloured by thickness (the
deck) or in the preview's colours, edges drawn, for the docs.

  .venv/bin/python scripts/render_mesh.py BASE.inp|P.glb OUT.png [--elev 30 --azim -60]
Reads the deck with meshio (nodes, elements, element sets) and the *SHELL SECTION thicknesses itself; the
preview with pygltflib (the triangles with their vertex colours, the outlines)."""

import argparse
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("deck")
    ap.add_argument("png")
    ap.add_argument("--elev", type=float, default=30)
    ap.add_argument("--azim", type=float, default=-60)
    a = ap.parse_args()
    if a.deck.endswith(".glb"):
        render_glb(a)
        return
    mesh = meshio.read(a.deck, file_format="abaqus")
    text = Path(a.deck).read_text()
    thickness = {
        m.group(1): float(m.group(2))
        for m in re.finditer(r"^\*SHELL SECTION, ELSET=(\w+).*\n([^,\n]+),", text, re.M)
    }
    polys, values = [], []
    for name, blocks in sorted(mesh.cell_sets.items()):
        if name not in thickness:
            continue
        for block, indices in enumerate(blocks):
            for i in indices:
                polys.append(mesh.points[mesh.cells[block].data[i]])
                values.append(thickness[name])
    values = np.array(values)
    bands = sorted(set(values))
    cmap = plt.get_cmap("viridis", max(len(bands), 2))
    colours = [cmap(bands.index(v)) for v in values]
    fig = plt.figure(figsize=(8, 6), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="k", linewidths=0.15))
    frame(ax, mesh.points, a)
    handles = [plt.Rectangle((0, 0), 1, 1, color=cmap(i)) for i in range(len(bands))]
    ax.legend(handles, [f"t = {b:g} mm" for b in bands], loc="upper left", fontsize=8)
    ax.set_title(f"{Path(a.deck).name}: {len(polys)} shells", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.png, bbox_inches="tight")


def frame(ax, pts, a) -> None:
    """Equal scale on the three axes, the box as long as the part (a long bracket fills the picture)."""
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    for setter, l, h in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        setter(l, h)
    ax.set_box_aspect(np.maximum(hi - lo, 1e-3 * (hi - lo).max()))
    ax.view_init(a.elev, a.azim)
    ax.set_axis_off()


def render_glb(a) -> None:
    import pygltflib
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    gltf = pygltflib.GLTF2().load(a.deck)
    blob = gltf.binary_blob()

    def read(index, dtype, width):
        acc = gltf.accessors[index]
        view = gltf.bufferViews[acc.bufferView]
        data = np.frombuffer(blob[view.byteOffset : view.byteOffset + view.byteLength], dtype=dtype)
        return data.reshape(-1, width) if width > 1 else data

    faces, outlines = gltf.meshes[0].primitives
    points = read(faces.attributes.POSITION, np.float32, 3)  # the mesh's mm: the node's scale is not applied
    linear = read(faces.attributes.COLOR_0, np.float32, 3)
    srgb = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055).clip(0, 1)
    triangles = read(faces.indices, np.uint32, 3)
    segments = read(outlines.indices, np.uint32, 2)
    fig = plt.figure(figsize=(8, 6), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(points[triangles], facecolors=srgb[triangles[:, 0]], linewidths=0))
    ax.add_collection3d(Line3DCollection(points[segments], colors="k", linewidths=0.15))
    frame(ax, points, a)
    ax.set_title(f"{Path(a.deck).name}: {len(points)} vertices, {len(triangles)} triangles", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.png, bbox_inches="tight")


if __name__ == "__main__":
    main()
