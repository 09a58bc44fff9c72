"""Entry point: `python -m midsurf_mesher faces PATH` or `python -m midsurf_mesher mesh` (request on stdin)."""

import ctypes
import json
import os
import sys

# personality(2) flag: no address space randomisation for the programs this process executes.
ADDR_NO_RANDOMIZE = 0x0040000
FIXED_LAYOUT_MARK = "MIDSURF_MESHER_FIXED_LAYOUT"


def run_with_fixed_layout() -> None:
    """gmsh orders some of its entities by memory address, so that with address space randomisation the same
    request gives one of two meshes (precursor_rf_shield: 3 and 5 of 8 runs). Linux: start again, once, with
    randomisation off (the same binary and libraries then give the same mesh). Where personality(2) is refused
    (a container's seccomp profile), go on as we are."""
    if not sys.platform.startswith("linux") or os.environ.get(FIXED_LAYOUT_MARK) == "1":
        return
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        current = libc.personality(0xFFFFFFFF)
        if current == -1 or libc.personality(current | ADDR_NO_RANDOMIZE) == -1:
            return
    except (OSError, AttributeError):
        return
    os.environ[FIXED_LAYOUT_MARK] = "1"
    os.execv(sys.executable, [sys.executable, "-m", "midsurf_mesher", *sys.argv[1:]])


def address_layout() -> str:
    """"fixed" when this process runs without address space randomisation, else "random"."""
    try:
        with open("/proc/self/personality") as f:
            return "fixed" if int(f.read(), 16) & ADDR_NO_RANDOMIZE else "random"
    except (OSError, ValueError):
        return "random"


def main() -> int:
    run_with_fixed_layout()
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

        payload = {**mesh(json.load(sys.stdin)), "address_layout": address_layout()}
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
