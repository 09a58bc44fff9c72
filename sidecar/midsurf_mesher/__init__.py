"""Shell meshing of a midsurf mid-surface STEP, run as its own process by `midsurf mesh`.

Two commands, each a separate process because the gmsh wheel brings its own OCCT, which must not share a
process with OCP's:
  python -m midsurf_mesher faces MID.step      (OCP) every named face: name, area, centroid, normal
  python -m midsurf_mesher mesh < request.json (gmsh) every gmsh surface's geometry and its elements
Both print one JSON object on stdout; errors go to stderr with exit code 2. Rust matches the two lists by
geometry (gmsh drops the face names and orders surfaces its own way) and writes the decks.
"""
