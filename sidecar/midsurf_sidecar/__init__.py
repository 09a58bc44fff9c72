"""The OCCT side of midsurf: answers NDJSON requests from the Rust binary (see ../PROTOCOL.md).

Layout, in the order a run uses it (each layer imports only the ones above it):
- `constants.py`: every tolerance, step and sample count the sidecar chooses itself, each with its reason.
- `protocol/`: args, errors, handle store; no OCP, so the server can answer `ocp_missing`.
- `geom/`: helpers shared by the stages (vectors, sub-shape maps, normals, interior points, booleans).
- the stages: `load/` (load_step), `describe/` (describe, mesh), `patch/` (make_patch), `fuse/` (fuse),
  `joints/` (probe_edges, extend_edges; gather merges a patch's pieces), `write/` (make_shells, write_step).
- `ops.py`: the op table, turning each request's args into one stage call.
- `server.py`: the request loop and handshake; `__main__.py`: `python -m midsurf_sidecar`.
"""
