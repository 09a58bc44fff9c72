"""Typed access to a request's `args`, raising BadArgs with the offending key in the message."""

import math
from typing import Any

from ..constants import ZERO_VECTOR
from .errors import BadArgs


def require_str(args: dict[str, Any], key: str) -> str:
    value = args.get(key)
    if not isinstance(value, str) or not value:
        raise BadArgs(f"`{key}` must be a non-empty string, got {value!r}")
    return value


def require_int(args: dict[str, Any], key: str, minimum: int = 0) -> int:
    value = args.get(key)
    # bool is an int subclass in Python; `true` is not a valid id.
    if not isinstance(value, int) or isinstance(value, bool) or value < minimum:
        raise BadArgs(f"`{key}` must be an integer >= {minimum}, got {value!r}")
    return value


def require_handle(args: dict[str, Any], key: str = "handle") -> int:
    return require_int(args, key, minimum=1)


def optional_bool(args: dict[str, Any], key: str, default: bool) -> bool:
    value = args.get(key, default)
    if not isinstance(value, bool):
        raise BadArgs(f"`{key}` must be true or false, got {value!r}")
    return value


def as_number(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise BadArgs(f"{what} must be a finite number, got {value!r}")
    return float(value)


def require_positive(args: dict[str, Any], key: str) -> float:
    value = as_number(args.get(key), f"`{key}`")
    if value <= 0:
        raise BadArgs(f"`{key}` must be > 0, got {value!r}")
    return value


def require_list(args: dict[str, Any], key: str) -> list[Any]:
    value = args.get(key)
    if not isinstance(value, list):
        raise BadArgs(f"`{key}` must be a list, got {value!r}")
    return value


def handle_list(args: dict[str, Any], key: str = "handles") -> list[int]:
    values = require_list(args, key)
    for value in values:
        if not isinstance(value, int) or isinstance(value, bool) or value < 1:
            raise BadArgs(f"`{key}` must hold positive integers, got {value!r}")
    return values


def require_number(args: dict[str, Any], key: str) -> float:
    return as_number(args.get(key), f"`{key}`")


def require_non_negative(args: dict[str, Any], key: str) -> float:
    value = require_number(args, key)
    if value < 0:
        raise BadArgs(f"`{key}` must be >= 0, got {value!r}")
    return value


def as_point(value: Any, what: str) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        raise BadArgs(f"{what} must be [x, y, z], got {value!r}")
    x, y, z = (as_number(c, f"each component of {what}") for c in value)
    return x, y, z


def require_point(args: dict[str, Any], key: str) -> tuple[float, float, float]:
    return as_point(args.get(key), f"`{key}`")


def require_direction(args: dict[str, Any], key: str) -> tuple[float, float, float]:
    """A non-zero vector, returned normalised."""
    x, y, z = require_point(args, key)
    length = math.sqrt(x * x + y * y + z * z)
    if length < ZERO_VECTOR:
        raise BadArgs(f"`{key}` must be a non-zero vector, got {[x, y, z]}")
    return x / length, y / length, z / length


def require_object(args: dict[str, Any], key: str) -> dict[str, Any]:
    value = args.get(key)
    if not isinstance(value, dict):
        raise BadArgs(f"`{key}` must be an object, got {value!r}")
    return value


def index_list(values: Any, count: int, what: str, owner: str) -> list[int]:
    """`values` as distinct 0-based indices below `count`; the message names the offending index.

    `what` names one index ("face"), `owner` what they index into ("the solid", "the fused shape").
    """
    if not isinstance(values, list):
        raise BadArgs(f"{what} ids must be a list, got {values!r}")
    seen: set[int] = set()
    for value in values:
        if not isinstance(value, int) or isinstance(value, bool):
            raise BadArgs(f"{what} ids must be integers, got {value!r}")
        if not 0 <= value < count:
            valid = f"ids 0..{count - 1}" if count else "none"
            raise BadArgs(f"{what} {value} out of range: {owner} has {count} {what}s ({valid})")
        if value in seen:
            raise BadArgs(f"{what} {value} is listed twice")
        seen.add(value)
    return values
