"""Shared plumbing: the owner of one native handle, numpy conversions, the progress trampoline.

Nothing here is public API; :mod:`progsim.hierarchy` and :mod:`progsim.simulation` build on it.
"""

from __future__ import annotations

import operator
import threading
from typing import Any, Callable, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._errors import (
    ClosedError,
    InvalidArgumentError,
    InvalidMeshError,
    WrongCallOrderError,
    make_error,
)
from ._progsim_cffi import ffi, lib

#: What ``progress=`` accepts: ``True`` (a tqdm bar), ``False``/``None`` (quiet), or a
#: callable ``(done, total, phase) -> bool`` whose true result cancels the call.
ProgressArg = Union[bool, None, Callable[[int, int, str], Any]]

_INT32_MIN = -(2**31)
_INT32_MAX = 2**31 - 1

# ------------------------------------------------------------------ native objects -------

_thread_state = threading.local()


def _in_callback() -> bool:
    return getattr(_thread_state, "callback_depth", 0) > 0


def decode(raw: "ffi.CData") -> str:
    """A C string (possibly NULL) as text."""
    return "" if raw == ffi.NULL else ffi.string(raw).decode("utf-8", "replace")


class NativeObject:
    """A Python object owning (or borrowing) one progsim handle.

    Subclasses set ``_last_error_fn`` (the ``ps_*_last_error`` of their handle type). Every C
    call goes through :meth:`_call`, which refuses closed objects and calls made from inside a
    progress callback (the C ABI forbids them), serialises calls on this handle (the C ABI
    allows one thread at a time per handle) and turns failures into exceptions.
    """

    _last_error_fn: Callable[["ffi.CData"], "ffi.CData"]

    def __init__(self) -> None:
        self._cdata: Optional["ffi.CData"] = None
        self._lock = threading.Lock()

    # -- lifetime -------------------------------------------------------------------------

    @property
    def closed(self) -> bool:
        """Whether :meth:`close` was called (then every other call raises :class:`ClosedError`)."""
        return self._cdata is None or not self._owner_open()

    def _owner_open(self) -> bool:
        """Whether whatever this object borrows its handle from is still open."""
        return True

    def close(self) -> None:
        """Releases the native object now. Safe to call more than once."""
        if _in_callback():
            raise WrongCallOrderError(
                f"{type(self).__name__}.close() was called from inside a progress callback"
            )
        with self._lock:
            cdata, self._cdata = self._cdata, None
            if cdata is not None:
                self._release(cdata)

    def _release(self, cdata: "ffi.CData") -> None:
        """Frees the handle (called once, by :meth:`close`)."""
        ffi.release(cdata)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info: Any) -> None:
        self.close()

    # -- calls ----------------------------------------------------------------------------

    def _handle(self) -> "ffi.CData":
        if _in_callback():
            raise WrongCallOrderError(
                "progsim cannot be called from inside a progress callback; return True from "
                "the callback to cancel instead"
            )
        cdata = self._cdata
        if cdata is None or not self._owner_open():
            raise ClosedError(f"this {type(self).__name__} is closed")
        return cdata

    def _call(self, function: Callable[..., int], *args: Any) -> None:
        """Calls ``function(handle, *args)`` and raises the exception of a failed status."""
        handle = self._handle()
        with self._lock:
            status = function(handle, *args)
            if status != lib.PS_OK:
                message = decode(type(self)._last_error_fn(handle))
        if status != lib.PS_OK:
            raise make_error(status, message)


def check_create(status: int) -> None:
    """Raises the exception of a failed create call (message from ``ps_last_error()``)."""
    if status != lib.PS_OK:
        raise make_error(status, decode(lib.ps_last_error()))


# ------------------------------------------------------------------ numpy ----------------


def int32_value(value: Any, name: str) -> int:
    """``value`` as a Python int that fits int32_t, or :class:`InvalidArgumentError`."""
    try:
        result = operator.index(value)
    except TypeError:
        raise InvalidArgumentError(f"{name} must be an integer, got {value!r}") from None
    if not _INT32_MIN <= result <= _INT32_MAX:
        raise InvalidArgumentError(f"{name} = {result} does not fit a 32-bit integer")
    return result


def real_value(value: Any, name: str) -> float:
    """``value`` as a Python float, or :class:`InvalidArgumentError` (range checks are the
    library's)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InvalidArgumentError(f"{name} must be a real number, got {value!r}") from None


def three_floats(value: Sequence[float], name: str) -> List[float]:
    """A 3-vector as a list of 3 floats, or :class:`InvalidArgumentError`."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InvalidArgumentError(f"{name} must be 3 real numbers, got {value!r}") from None
    if array.shape != (3,):
        raise InvalidArgumentError(f"{name} must have 3 components, got shape {array.shape}")
    return array.tolist()


def vec3(value: Optional[Sequence[float]], name: str) -> "ffi.CData":
    """A 3-vector as a ``double[3]`` (NULL for None)."""
    if value is None:
        return ffi.NULL
    return ffi.new("double[3]", three_floats(value, name))


def as_vertices(vertices: Any, name: str = "vertices") -> np.ndarray:
    """``vertices`` as a C-contiguous float64 (n, 3) array, copied only if needed."""
    array = np.asarray(vertices)
    if array.ndim != 2 or array.shape[1] != 3:
        raise InvalidArgumentError(f"{name} must have shape (n, 3), got {array.shape}")
    if array.dtype.kind not in "fiu":
        raise InvalidArgumentError(f"{name} must be real numbers, got dtype {array.dtype}")
    return np.ascontiguousarray(array, dtype=np.float64)


def as_indices(indices: Any, name: str, shape: str, error=InvalidArgumentError) -> np.ndarray:
    """``indices`` as a C-contiguous int32 array, copied only if needed.

    ``shape`` is ``"(m, 3)"``, ``"(k, 4)"`` or ``"(k,)"`` (the number after the comma is the
    column count); integer arrays of other widths are accepted when every value fits int32
    (``error`` is raised otherwise: no silent wrap-around).
    """
    array = np.asarray(indices)
    if shape == "(k,)":
        if array.ndim != 1:
            raise InvalidArgumentError(f"{name} must be a 1-D sequence, got shape {array.shape}")
    else:
        columns = int(shape.rstrip(")").rsplit(",", 1)[1])
        if array.ndim != 2 or array.shape[1] != columns:
            raise InvalidArgumentError(f"{name} must have shape {shape}, got {array.shape}")
    if array.size == 0:
        return np.ascontiguousarray(array, dtype=np.int32)
    if array.dtype.kind not in "iu":
        raise InvalidArgumentError(f"{name} must be integers, got dtype {array.dtype}")
    if array.dtype != np.int32:
        low, high = int(array.min()), int(array.max())
        if low < _INT32_MIN or high > _INT32_MAX:
            bad = low if low < _INT32_MIN else high
            raise error(f"{name} holds the index {bad}, which does not fit a 32-bit integer")
    return np.ascontiguousarray(array, dtype=np.int32)


def as_faces(faces: Any) -> np.ndarray:
    """``faces`` as a C-contiguous int32 (m, 3) array."""
    return as_indices(faces, "faces", "(m, 3)", error=InvalidMeshError)


def as_tets(tets: Any) -> np.ndarray:
    """``tets`` as a C-contiguous int32 (k, 4) array."""
    return as_indices(tets, "tets", "(k, 4)", error=InvalidMeshError)


def index_buffer(values: Optional[Sequence[int]], name: str) -> Tuple[np.ndarray, "ffi.CData"]:
    """``values`` as an int32 array and a cffi buffer over it (NULL when empty); keep both
    alive while C borrows the buffer."""
    array = as_indices([] if values is None else values, name, "(k,)")
    return array, (ffi.from_buffer("int32_t[]", array) if array.size else ffi.NULL)


def output_array(
    out: Optional[np.ndarray], rows: int, dtype: Any, name: str, columns: int = 3
) -> np.ndarray:
    """A writable C-contiguous (rows, columns) array of ``dtype``: ``out`` itself, or a new
    one."""
    if out is None:
        return np.empty((rows, columns), dtype=dtype)
    if not isinstance(out, np.ndarray):
        raise InvalidArgumentError(f"{name} must be a numpy array")
    if out.dtype != np.dtype(dtype) or out.shape != (rows, columns):
        raise InvalidArgumentError(
            f"{name} must be a {np.dtype(dtype).name} array of shape ({rows}, {columns}), "
            f"got {out.dtype.name} {out.shape}"
        )
    if not out.flags.c_contiguous or not out.flags.writeable:
        raise InvalidArgumentError(f"{name} must be C-contiguous and writable")
    return out


def fetch_rows(
    call: Callable[..., None],
    function: Any,
    where: Tuple[int, ...],
    dtype: Any,
    out: Optional[np.ndarray],
    columns: int = 3,
) -> np.ndarray:
    """Runs the C ABI's size-then-fill protocol for a (rows, columns) array.

    ``call(function, *args)`` is the owner's checked call; ``function`` a ps_*_get_* entry
    point taking (handle, *where, buffer, capacity, count), ``where`` being (level,) or
    (level, frame).
    """
    ctype = "double[]" if np.dtype(dtype) == np.float64 else "int32_t[]"
    count = ffi.new("size_t*")
    call(function, *where, ffi.NULL, 0, count)
    array = output_array(out, count[0] // columns, dtype, "out", columns)
    buffer = ffi.from_buffer(ctype, array, require_writable=True)
    call(function, *where, buffer, array.size, count)
    return array


# ------------------------------------------------------------------ progress -------------


class ProgressRun:
    """The Python side of one long call's progress callback.

    Reports go to a tqdm bar (``progress=True``), to a user callable, or nowhere. The
    trampoline is installed even without a reporter, so that Ctrl-C (KeyboardInterrupt)
    cancels a long call cleanly. Any exception raised while reporting is kept, the call is
    cancelled, and :meth:`reraise` raises it once the C call has returned.
    """

    def __init__(
        self, progress: ProgressArg, total: Optional[int] = None, phase: Optional[str] = None
    ) -> None:
        """``total`` and ``phase``, when known, open the bar before the first report."""
        if not (progress is None or isinstance(progress, bool) or callable(progress)):
            raise InvalidArgumentError(
                f"progress must be True, False or a callable (done, total, phase) -> bool, "
                f"got {progress!r}"
            )
        self._progress = progress
        self._bar = None
        self._phase: Optional[str] = None
        self.error: Optional[BaseException] = None
        if progress is True and total is not None and phase is not None:
            self._update_bar(0, total, phase)

    def report(self, done: int, total: int, phase: str) -> bool:
        """Handles one report; returns True to cancel."""
        if self._progress is True:
            self._update_bar(done, total, phase)
            return False
        if callable(self._progress):
            return bool(self._progress(done, total, phase))
        return False

    def _update_bar(self, done: int, total: int, phase: str) -> None:
        """One bar while the reports count up to the same total (a phase that only renames
        the stage, such as each load step of an accuracy run, relabels it); a new bar when
        the total changes or the count starts over."""
        if self._bar is None or total != self._bar.total or done < self._bar.n:
            self.close()
            from tqdm.auto import tqdm

            self._bar = tqdm(total=total, desc=phase, unit="step", leave=True)
        elif phase != self._phase:
            self._bar.set_description(phase, refresh=False)
        self._phase = phase
        self._bar.update(done - self._bar.n)

    def install(self, definition: "ffi.CData") -> None:
        """Points a def's ``progress`` and ``progress_user_data`` at this run; the handle
        lives as long as the run does."""
        self._handle = ffi.new_handle(self)
        definition.progress = lib._progsim_progress
        definition.progress_user_data = self._handle

    def close(self) -> None:
        """Closes the progress bar, if any."""
        if self._bar is not None:
            bar, self._bar = self._bar, None
            bar.close()

    def reraise(self) -> None:
        """Raises the exception kept from the callback, if any."""
        if self.error is not None:
            error, self.error = self.error, None
            raise error


def _on_trampoline_error(exc_type, exc_value, traceback) -> None:
    """Keeps an exception raised outside the trampoline's own try (e.g. a KeyboardInterrupt
    landing on its first line) for the Python caller instead of printing it."""
    # cffi passes the traceback whose first frame is the trampoline's own.
    frame_locals = traceback.tb_frame.f_locals if traceback is not None else {}
    try:
        run = ffi.from_handle(frame_locals["user_data"])
    except Exception:  # nothing to attach it to: cffi's default report is all we can do
        return
    if run.error is None:
        run.error = exc_value


@ffi.def_extern(error=1, onerror=_on_trampoline_error)
def _progsim_progress(user_data, done, total, phase):  # noqa: D401 - C callback
    """The ps_progress_fn trampoline: forwards to the ProgressRun behind user_data."""
    run: ProgressRun = ffi.from_handle(user_data)
    _thread_state.callback_depth = getattr(_thread_state, "callback_depth", 0) + 1
    try:
        return 1 if run.report(done, total, decode(phase)) else 0
    except BaseException as error:  # noqa: B902 - must not propagate into C
        run.error = error
        return 1
    finally:
        _thread_state.callback_depth -= 1
