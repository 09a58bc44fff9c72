"""Exceptions that carry a protocol error code, so the request loop can answer instead of dying."""


class OpError(Exception):
    """A failure reported to Rust as `{"err": {"code": code, "message": message}}`."""

    code = "kernel_error"

    def __init__(self, message: str, code: str | None = None) -> None:
        super().__init__(message)
        if code is not None:
            self.code = code


class BadArgs(OpError):
    """The request's arguments are missing or invalid: a bug on the Rust side."""

    code = "bad_args"


class KernelError(OpError):
    """OCCT failed or returned something unusable; the message says which step and on what."""

    code = "kernel_error"


def one_line(exc: BaseException) -> str:
    """The exception as one line; foreign exceptions (OCCT's Standard_Failure...) keep their type name."""
    text = " ".join(str(exc).split())
    if isinstance(exc, OpError):
        return text
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__
