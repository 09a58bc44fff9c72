"""One gmsh attempt in a forked child with a time limit: gmsh cannot be interrupted inside a call, and on some
faces it runs for ever (ploopy_headband_triangle: over 10 minutes in one surface) or crashes. The child starts
from the parent's gmsh model (fork copies it), sends its result back as JSON through a pipe, and is killed when
the time is up."""

import json
import os
import select
import signal
import time
from dataclasses import dataclass
from typing import Any, Callable

from midsurf_sidecar.lifeline import tie_to_parent


@dataclass
class Outcome:
    """`value` when the child finished, else why not: "timed out after N s", "crashed (signal N)" or the
    exception's message."""

    value: Any = None
    failure: str = ""


def in_child(attempt: Callable[[], Any], time_limit_s: float) -> Outcome:
    parent = os.getpid()
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        # Die with the mesher whatever kills it (fork does not inherit the parent-death signal).
        os.environ["MIDSURF_PARENT_PID"] = str(parent)
        tie_to_parent()
        try:
            reply = {"value": attempt()}
        except Exception as e:  # gmsh raises plain Exceptions carrying its last error
            reply = {"failure": str(e) or type(e).__name__}
        data = json.dumps(reply, separators=(",", ":")).encode()
        with os.fdopen(write, "wb") as pipe:
            pipe.write(data)
        os._exit(0)
    os.close(write)
    chunks, deadline = [], time.monotonic() + time_limit_s
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([read], [], [], left)[0]:
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                return Outcome(failure=f"timed out after {time_limit_s:.3g} s")
            chunk = os.read(read, 1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
    finally:
        os.close(read)
    _, status = os.waitpid(pid, 0)
    if not chunks:
        return Outcome(failure=f"crashed (signal {os.WTERMSIG(status)})" if os.WIFSIGNALED(status) else "crashed")
    reply = json.loads(b"".join(chunks))
    return Outcome(value=reply.get("value"), failure=reply.get("failure", ""))
