"""Handle store: shapes stay in the sidecar, Rust refers to them by positive integers never reused."""

from typing import Any

from .errors import BadArgs


class HandleStore:
    """Append-only numbering of shapes; `free` drops a shape but never recycles its number."""

    def __init__(self) -> None:
        self._shapes: dict[int, Any] = {}
        self._last = 0

    def put(self, shape: Any) -> int:
        self._last += 1
        self._shapes[self._last] = shape
        return self._last

    def get(self, handle: int) -> Any:
        try:
            return self._shapes[handle]
        except KeyError:
            raise BadArgs(f"no shape with handle {handle} (never created or already freed)") from None

    def free(self, handles: list[int]) -> int:
        """Drops the given handles; unknown ones are ignored. Returns how many were dropped."""
        return sum(1 for h in handles if self._shapes.pop(h, None) is not None)
