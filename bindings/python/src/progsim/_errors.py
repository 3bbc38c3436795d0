"""The exception hierarchy: one class per ``ps_status`` code of the C ABI."""

from __future__ import annotations

from typing import Callable, Dict, Optional, Type

from ._progsim_cffi import ffi, lib

__all__ = [
    "ProgsimError",
    "InvalidArgumentError",
    "InvalidMeshError",
    "InvalidSceneError",
    "ProgsimIOError",
    "NumericalError",
    "WrongCallOrderError",
    "OutOfRangeError",
    "CancelledError",
    "IntersectingError",
    "InternalError",
    "NullArgumentError",
    "BufferTooSmallError",
    "UninitializedDefError",
    "VersionMismatchError",
    "OutOfMemoryError",
    "UnsupportedError",
    "ClosedError",
]


class ProgsimError(Exception):
    """A progsim call failed.

    Attributes:
        message: the library's message, naming the failed call and the problem.
        status: the stable name of the status code, e.g. ``"PS_ERROR_INVALID_MESH"``.
        code: the numeric ``ps_status`` value (``None`` for errors raised by Python alone).
    """

    #: The ``ps_status`` value this class stands for (``None`` on the base class).
    CODE: Optional[int] = None

    def __init__(self, message: str, status: Optional[str] = None, code: Optional[int] = None):
        if code is None:
            code = self.CODE
        if status is None:
            status = status_name(code) if code is not None else "PS_ERROR_UNKNOWN_STATUS"
        super().__init__(message)
        self.message = message
        self.status = status
        self.code = code

    def __str__(self) -> str:
        return self.message

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}({self.message!r}, status={self.status!r}, code={self.code!r})"
        )

    def __reduce__(self):  # keeps status and code through pickling (multiprocessing)
        return (type(self), (self.message, self.status, self.code))


class InvalidArgumentError(ProgsimError, ValueError):
    """A parameter is NaN, out of range, of the wrong shape, or unknown
    (``PS_ERROR_INVALID_ARGUMENT``)."""

    CODE = 1


class InvalidMeshError(ProgsimError, ValueError):
    """A mesh fails validation; the message names the first bad element
    (``PS_ERROR_INVALID_MESH``)."""

    CODE = 2


class InvalidSceneError(ProgsimError, ValueError):
    """A scene is malformed; the message gives the JSON path (``PS_ERROR_INVALID_SCENE``)."""

    CODE = 3


class ProgsimIOError(ProgsimError, OSError):
    """A file cannot be read or written (``PS_ERROR_IO``)."""

    CODE = 4


class NumericalError(ProgsimError, ArithmeticError):
    """The solver failed: non-finite values or a failed factorization (``PS_ERROR_NUMERICAL``)."""

    CODE = 5


class WrongCallOrderError(ProgsimError, RuntimeError):
    """The call needs another call first (``PS_ERROR_WRONG_CALL_ORDER``)."""

    CODE = 6


class OutOfRangeError(ProgsimError, IndexError):
    """A level, handle or index does not exist (``PS_ERROR_OUT_OF_RANGE``)."""

    CODE = 7


class CancelledError(ProgsimError):
    """The progress callback asked to stop (``PS_ERROR_CANCELLED``); the state is that of the
    last completed step."""

    CODE = 8


class IntersectingError(ProgsimError):
    """A configuration intersects itself or another body (``PS_ERROR_INTERSECTING``)."""

    CODE = 9


class InternalError(ProgsimError, RuntimeError):
    """A bug in progsim; please report the message (``PS_ERROR_INTERNAL``)."""

    CODE = 10


class NullArgumentError(ProgsimError, ValueError):
    """A required pointer or handle was NULL (``PS_ERROR_NULL_ARGUMENT``)."""

    CODE = 11


class BufferTooSmallError(ProgsimError, ValueError):
    """An output buffer is too small (``PS_ERROR_BUFFER_TOO_SMALL``)."""

    CODE = 12


class UninitializedDefError(ProgsimError):
    """A def-struct was not filled by its ``*_def_init()`` (``PS_ERROR_UNINITIALIZED_DEF``)."""

    CODE = 13


class VersionMismatchError(ProgsimError, ImportError):
    """The loaded library cannot serve these bindings (``PS_ERROR_VERSION_MISMATCH``)."""

    CODE = 14


class OutOfMemoryError(ProgsimError, MemoryError):
    """An allocation failed (``PS_ERROR_OUT_OF_MEMORY``)."""

    CODE = 15


class UnsupportedError(ProgsimError, NotImplementedError):
    """A valid request that this version cannot do yet (``PS_ERROR_UNSUPPORTED``)."""

    CODE = 16


class ClosedError(NullArgumentError):
    """The object was closed (or its owner was): its native handle is gone.

    Raised by Python before any C call; like a NULL handle in C, so it is a
    :class:`NullArgumentError` (and a :class:`ValueError`, as for a closed file)."""


_BY_CODE: Dict[int, Type[ProgsimError]] = {
    cls.CODE: cls
    for cls in (
        InvalidArgumentError,
        InvalidMeshError,
        InvalidSceneError,
        ProgsimIOError,
        NumericalError,
        WrongCallOrderError,
        OutOfRangeError,
        CancelledError,
        IntersectingError,
        InternalError,
        NullArgumentError,
        BufferTooSmallError,
        UninitializedDefError,
        VersionMismatchError,
        OutOfMemoryError,
        UnsupportedError,
    )
    if cls.CODE is not None
}


def status_name(code: int) -> str:
    """The stable name of status ``code``, e.g. ``"PS_ERROR_INVALID_MESH"``."""
    return ffi.string(lib.ps_status_name(code)).decode("utf-8", "replace")


def error_class(code: int) -> Type[ProgsimError]:
    """The exception class of status ``code`` (:class:`ProgsimError` for unknown codes)."""
    return _BY_CODE.get(code, ProgsimError)


def make_error(code: int, message: str) -> ProgsimError:
    """The exception for a failed call that returned ``code`` with ``message``."""
    return error_class(code)(message or status_name(code), status_name(code), code)


def check(status: int, last_error: Callable[[], "ffi.CData"]) -> None:
    """Raises the exception of ``status`` unless it is ``PS_OK``.

    ``last_error`` returns the C string with the failure's message (``ps_last_error``,
    ``ps_sim_last_error(sim)``...); it is called only on failure, right after the call.
    """
    if status == lib.PS_OK:
        return
    raw = last_error()
    message = ffi.string(raw).decode("utf-8", "replace") if raw != ffi.NULL else ""
    raise make_error(status, message)
