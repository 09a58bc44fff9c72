"""Renders a `midsurf mesh` Abaqus deck (.inp) to a PNG: shells coloured by thickness, edges drawn, for the docs.

  .venv/bin/python scripts/render_mesh.py BASE.inp OUT.png [--elev 30 --azim -60]
Reads the deck with meshio (nodes, elements, element sets) and the *SHELL SECTION thicknesses itself."""

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
    pts = mesh.points
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(a.elev, a.azim)
    ax.set_axis_off()
    handles = [plt.Rectangle((0, 0), 1, 1, color=cmap(i)) for i in range(len(bands))]
    ax.legend(handles, [f"t = {b:g} mm" for b in bands], loc="upper left", fontsize=8)
    ax.set_title(f"{Path(a.deck).name}: {len(polys)} shells", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.png)


if __name__ == "__main__":
    main()
