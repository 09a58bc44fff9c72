"""Entry point: `python -m midsurf_sidecar`, spoken to over stdin/stdout (PROTOCOL.md)."""

import os
import sys
from typing import TextIO


def protocol_stream() -> TextIO:
    """A private copy of stdout for protocol lines; fd 1 itself is pointed at stderr.

    OCCT prints to C++ std::cout (fd 1) whenever it likes. This must run before OCP is imported so
    nothing but protocol lines can reach the real stdout.
    """
    protocol_fd = os.dup(1)
    os.dup2(2, 1)
    return os.fdopen(protocol_fd, "w", encoding="utf-8", newline="\n")


def main() -> int:
    from .lifeline import tie_to_parent

    tie_to_parent()
    replies = protocol_stream()
    from .server import serve

    serve(sys.stdin.buffer, replies)
    replies.flush()
    return 0


def leave(code: int) -> None:
    """Exits without the interpreter's teardown.

    Every reply is flushed and every output file was written and renamed by its op, so nothing is lost; the
    teardown would only free OCCT's objects one by one (about 0.3 s, a third of the I/O floor of a small part),
    which the operating system does at once.
    """
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


if __name__ == "__main__":
    leave(main())
