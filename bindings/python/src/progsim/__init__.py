"""progsim: progressive (level-of-detail) simulation of cloth and thin shells.

Python bindings of the progsim C ABI (``progsim.h``) through cffi. Units are SI throughout
(metres, seconds, kilograms, pascals, radians); positions are float64 (n, 3) numpy arrays,
faces int32 (m, 3) arrays.

Example::

    import progsim

    with progsim.Hierarchy.from_file("scenes/meshes/square_cloth.obj") as hierarchy:
        with progsim.Simulation(hierarchy, pinned=[420, 440], gravity=(0, 0, -9.81)) as sim:
            sim.step_preview(25, progress=True)
            print(sim.positions()[:, 2].min(), sim.level_stats())

Every failure raises a :class:`ProgsimError` subclass carrying the library's message, its
status name (``.status``) and code (``.code``).
"""

from __future__ import annotations

from ._progsim_cffi import ffi as _ffi, lib as _lib
from . import _errors
from ._errors import (  # noqa: F401 - re-exported through __all__
    BufferTooSmallError,
    CancelledError,
    ClosedError,
    IntersectingError,
    InternalError,
    InvalidArgumentError,
    InvalidMeshError,
    InvalidSceneError,
    NullArgumentError,
    NumericalError,
    OutOfMemoryError,
    OutOfRangeError,
    ProgsimError,
    ProgsimIOError,
    UninitializedDefError,
    UnsupportedError,
    VersionMismatchError,
    WrongCallOrderError,
    status_name,
)

#: Version of this Python package.
__version__ = "0.20.0"

#: The header version these bindings were compiled against (major·10000 + minor·100 + patch).
HEADER_VERSION: int = _lib.PS_VERSION_HEADER

if _lib.ps_check_version(HEADER_VERSION) != _lib.PS_OK:
    raise VersionMismatchError(_ffi.string(_lib.ps_last_error()).decode("utf-8", "replace"))

from ._native import int32_value  # noqa: E402 - after the version check
from .accuracy import Accuracy, AccuracyRow  # noqa: E402
from .hierarchy import Hierarchy  # noqa: E402
from .simulation import (  # noqa: E402
    CHOICES,
    EFFECTS,
    INTERPOLATIONS,
    KINDS,
    LOAD_DISTRIBUTIONS,
    MODES,
    PARAMETERS,
    PREDICTIONS,
    STEP_STATS_DTYPE,
    DynamicLevelStats,
    Frame,
    HandleReaction,
    LevelStats,
    RefinementStats,
    Simulation,
    StrainCorrectionStats,
)


def library_version() -> str:
    """The loaded libprogsim's version as text, e.g. ``"0.20.0"``."""
    return _ffi.string(_lib.ps_version_string()).decode("ascii")


def library_version_number() -> int:
    """The loaded libprogsim's version packed as major·10000 + minor·100 + patch."""
    return int(_lib.ps_version())


def set_threads(threads: int) -> None:
    """Fixes the threads of progsim's parallel loops for the whole process (1 to 1024), or
    ``0`` to let the library choose (the default): the cores other processes leave idle,
    sampled every 0.25 s while it computes, so that a loaded machine needs no
    ``OMP_WAIT_POLICY``. ``OMP_NUM_THREADS``, if set, caps the automatic count.

    Raises :class:`InvalidArgumentError` for any other value (the setting is then unchanged).
    """
    _errors.check(_lib.ps_set_threads(int32_value(threads, "threads")), _lib.ps_last_error)


def threads() -> tuple[int, int]:
    """``(setting, current)``: the value of :func:`set_threads` (0: automatic) and the threads
    a large parallel loop gets now."""
    setting = _ffi.new("int32_t*")
    current = _ffi.new("int32_t*")
    _errors.check(_lib.ps_get_threads(setting, current), _lib.ps_last_error)
    return int(setting[0]), int(current[0])


__all__ = [
    "Accuracy",
    "AccuracyRow",
    "Hierarchy",
    "Simulation",
    "LevelStats",
    "RefinementStats",
    "StrainCorrectionStats",
    "DynamicLevelStats",
    "Frame",
    "HandleReaction",
    "STEP_STATS_DTYPE",
    "CHOICES",
    "EFFECTS",
    "INTERPOLATIONS",
    "KINDS",
    "LOAD_DISTRIBUTIONS",
    "MODES",
    "PARAMETERS",
    "PREDICTIONS",
    "HEADER_VERSION",
    "library_version",
    "library_version_number",
    "set_threads",
    "threads",
    "status_name",
] + list(_errors.__all__)
