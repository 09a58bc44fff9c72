"""The sidecar dies with its parent, whatever kills the parent (SIGKILL included).

Linux: prctl(PR_SET_PDEATHSIG, SIGKILL) asks the kernel to kill this process when its parent goes. The parent
may already be gone by then (killed between fork and this call), so the parent's pid, passed by midsurf in
MIDSURF_PARENT_PID, is compared with ours afterwards. Elsewhere nothing is done: a dead parent closes our
stdin and the request loop ends at its next read.
"""

import ctypes
import os
import signal
import sys

PR_SET_PDEATHSIG = 1


def tie_to_parent() -> None:
    # midsurf blocks its stop signals to take them in one thread; the mask is inherited through exec.
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGTERM, signal.SIGINT, signal.SIGHUP})
    expected = os.environ.get("MIDSURF_PARENT_PID")
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if expected is not None and expected.isdigit() and os.getppid() != int(expected):
        os._exit(1)
