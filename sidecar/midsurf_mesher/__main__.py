"""Entry point: `python -m midsurf_mesher faces PATH` or `python -m midsurf_mesher mesh` (request on stdin)."""

import json
import os
import sys


def main() -> int:
    # gmsh can run for minutes: die with midsurf, whatever stops it (as the sidecar does).
    from midsurf_sidecar.lifeline import tie_to_parent

    tie_to_parent()
    # Only our JSON goes to stdout: the kernels print to fd 1, so keep a dup of it and point fd 1 at stderr.
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    if len(sys.argv) == 3 and sys.argv[1] == "faces":
        from .faces import named_faces

        payload = named_faces(sys.argv[2])
    elif len(sys.argv) == 2 and sys.argv[1] == "mesh":
        from .gmsh_mesh import mesh

        payload = mesh(json.load(sys.stdin))
    else:
        print("usage: python -m midsurf_mesher faces PATH | mesh < request.json", file=sys.stderr)
        return 2
    if "error" in payload:
        print(payload["error"], file=sys.stderr)
        return 2
    json.dump(payload, out, separators=(",", ":"))
    out.write("\n")
    out.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
