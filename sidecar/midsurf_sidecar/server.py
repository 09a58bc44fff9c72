"""The request loop: one NDJSON request in, one NDJSON reply out, in order, until shutdown or end of input.

OCP is imported by the `hello` op, not here, so that a Python without OCP can still answer `ocp_missing`.
"""

import json
import os
import platform
import sys
import time
import traceback
from typing import Any, BinaryIO, TextIO

from .protocol.args import require_int
from .protocol.errors import BadArgs, OpError, one_line
from .protocol.handles import HandleStore

PROTOCOL_VERSION = 2


class Session:
    """State across requests: the handshake outcome and the handle store."""

    def __init__(self) -> None:
        self.store = HandleStore()
        self.ops: dict[str, Any] | None = None
        self.finished = False

    def respond(self, line: bytes) -> dict[str, Any]:
        """The reply to one request line; never raises for a bad request or a failing op."""
        try:
            request = json.loads(line)
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            return _err(None, BadArgs(f"request is not a JSON object on one line: {one_line(exc)}"))
        request_id = request.get("id") if isinstance(request, dict) else None
        if not isinstance(request_id, int) or isinstance(request_id, bool) or request_id < 0:
            return _err(None, BadArgs(f'request needs an unsigned integer "id": {line[:200]!r}'))
        try:
            return {"id": request_id, "ok": self._run(request)}
        except OpError as exc:
            return _err(request_id, exc)
        except Exception as exc:
            # OCCT's exceptions (Standard_Failure...) and anything unforeseen: keep serving.
            traceback.print_exc(file=sys.stderr)
            return _err(request_id, OpError(f"{request.get('op')}: {one_line(exc)}"))

    def _run(self, request: dict[str, Any]) -> dict[str, Any]:
        op = request.get("op")
        if not isinstance(op, str):
            raise BadArgs(f'"op" must be a string, got {op!r}')
        args = request.get("args", {})
        if not isinstance(args, dict):
            raise BadArgs(f'"args" must be an object, got {args!r}')
        if op == "hello":
            return self._hello(args)
        if op == "shutdown":
            # Honoured even before the handshake: a process asked to quit should quit.
            self.finished = True
            return {"bye": True}
        if self.ops is None:
            raise OpError(f"{op!r} before hello: the first request must be hello", "no_handshake")
        if op not in self.ops:
            raise OpError(f"unknown op {op!r}; known: hello, shutdown, {', '.join(self.ops)}", "unknown_op")
        started = time.perf_counter()
        try:
            result = _profiled(self.ops[op], self.store, args)
        except Exception as error:
            _trace(f"{op} failed", time.perf_counter() - started, str(error))
            raise
        _trace(op, time.perf_counter() - started)
        _test_stall(op)
        _test_crash(op)
        return result

    def _hello(self, args: dict[str, Any]) -> dict[str, Any]:
        version = require_int(args, "protocol")
        if version != PROTOCOL_VERSION:
            raise OpError(
                f"midsurf speaks protocol {version}, this sidecar speaks {PROTOCOL_VERSION}: "
                "run scripts/setup to install matching versions",
                "protocol_mismatch",
            )
        try:
            from . import ops
        except ImportError as exc:
            raise OpError(f"cannot import OCP ({one_line(exc)}); run scripts/setup", "ocp_missing") from exc
        self.ops = ops.OPS
        return {"protocol": PROTOCOL_VERSION, "python": platform.python_version(), "occt": ops.occt_version()}


# Profiling (docs/benchmarks.md): MIDSURF_TRACE_OPS=FILE appends "op seconds" per request to FILE ("op failed
# seconds" for one that raised, then "# " and the first line of its error).
TRACE_VAR = "MIDSURF_TRACE_OPS"


# MIDSURF_PROFILE_OPS=FILE profiles every op (cProfile) and writes the stats so far to FILE after each one.
PROFILE_VAR = "MIDSURF_PROFILE_OPS"
_profile: Any = None


def _profiled(run: Any, store: HandleStore, args: dict[str, Any]) -> dict[str, Any]:
    global _profile
    path = os.environ.get(PROFILE_VAR)
    if not path:
        return run(store, args)
    import cProfile

    _profile = _profile or cProfile.Profile()
    try:
        return _profile.runcall(run, store, args)
    finally:
        _profile.dump_stats(path)


def _trace(op: str, seconds: float, why: str = "") -> None:
    path = os.environ.get(TRACE_VAR)
    if path:
        line = f"{op} {seconds:.6f}\n"
        if why:
            line += f"# {why.splitlines()[0]}\n"
        with open(path, "a", encoding="utf-8") as trace:
            trace.write(line)


# Fault injection for tests only: MIDSURF_TEST_STALL="OP:MARKER" makes the sidecar, once OP has run (its
# effects made, e.g. a STEP temporary written), write its pid to the file MARKER and hang instead of replying,
# so that a test can kill it, or midsurf, in the middle of a long operation at a known point.
TEST_STALL_VAR = "MIDSURF_TEST_STALL"
TEST_STALL_SECONDS = 600


def _test_stall(op: str) -> None:
    spec = os.environ.get(TEST_STALL_VAR, "")
    stall_op, _, marker = spec.partition(":")
    if not spec or stall_op != op or not marker:
        return
    with open(marker, "w", encoding="utf-8") as f:
        f.write(str(os.getpid()))
    time.sleep(TEST_STALL_SECONDS)


# Fault injection for tests only: MIDSURF_TEST_CRASH="OP:MARKER" makes the sidecar abort (SIGABRT, a crash of
# its own, as a kernel segfault is) once OP has run, the first time only: it first creates the file MARKER, and
# a sidecar that finds MARKER there goes on. With no MARKER it crashes every time.
TEST_CRASH_VAR = "MIDSURF_TEST_CRASH"


def _test_crash(op: str) -> None:
    spec = os.environ.get(TEST_CRASH_VAR, "")
    crash_op, _, marker = spec.partition(":")
    if not spec or crash_op != op:
        return
    if marker:
        if os.path.exists(marker):
            return
        with open(marker, "w", encoding="utf-8") as f:
            f.write(str(os.getpid()))
    os.abort()


def _err(request_id: int | None, exc: OpError) -> dict[str, Any]:
    return {"id": request_id, "err": {"code": exc.code, "message": one_line(exc)}}


def encode(reply: dict[str, Any]) -> str:
    """One protocol line. NaN/inf are not JSON: a reply holding one becomes a kernel_error."""
    try:
        return json.dumps(reply, separators=(",", ":"), allow_nan=False)
    except ValueError:
        message = "the result holds a NaN or infinite number (degenerate geometry?)"
        return json.dumps(_err(reply.get("id"), OpError(message)), separators=(",", ":"))


def serve(requests: BinaryIO, replies: TextIO) -> None:
    """Answers requests until `shutdown` or end of input."""
    session = Session()
    for line in iter(requests.readline, b""):
        if not line.strip():
            continue
        replies.write(encode(session.respond(line)) + "\n")
        replies.flush()
        if session.finished:
            return
