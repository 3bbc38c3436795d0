"""Simulations (``ps_sim``): preview steps, refinement, results."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import (
    Any,
    Dict,
    FrozenSet,
    Iterable,
    Iterator,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    Union,
)

import numpy as np

from ._errors import InvalidArgumentError, make_error
from ._native import (
    NativeObject,
    ProgressArg,
    ProgressRun,
    _thread_state,
    as_faces,
    as_indices,
    as_vertices,
    check_create,
    decode,
    int32_value,
    fetch_rows,
    index_buffer,
    real_value,
    three_floats,
    vec3,
)
from ._progsim_cffi import ffi, lib
from .hierarchy import Hierarchy, PathLike

__all__ = [
    "Simulation",
    "LevelStats",
    "RefinementStats",
    "DynamicLevelStats",
    "Frame",
    "STEP_STATS_DTYPE",
    "EFFECTS",
    "MODES",
    "PREDICTIONS",
    "INTERPOLATIONS",
    "KINDS",
    "PARAMETERS",
]

#: Effect names and their ``ps_effect`` bits.
EFFECTS: Dict[str, int] = {
    "membrane": lib.PS_EFFECT_MEMBRANE,
    "bending": lib.PS_EFFECT_BENDING,
    "gravity": lib.PS_EFFECT_GRAVITY,
    "pressure": lib.PS_EFFECT_PRESSURE,
    "contact": lib.PS_EFFECT_CONTACT,
    "friction": lib.PS_EFFECT_FRICTION,
    "strain_limit": lib.PS_EFFECT_STRAIN_LIMIT,
    "wind": lib.PS_EFFECT_WIND,
    "elasticity": lib.PS_EFFECT_ELASTICITY,
}

#: Step modes and their ``ps_mode`` values.
MODES: Dict[str, int] = {
    "dynamic": lib.PS_MODE_DYNAMIC,
    "quasistatic": lib.PS_MODE_QUASISTATIC,
}

#: How a progressive animation's finer levels predict their steps (``ps_prediction``):
#: ``velocity_only`` (PD++, the default), ``prolonged_positions`` (PD eq. 5), ``per_frame``
#: (PSQ per frame, for comparison).
PREDICTIONS: Dict[str, int] = {
    "velocity_only": lib.PS_PREDICTION_VELOCITY_ONLY,
    "prolonged_positions": lib.PS_PREDICTION_PROLONGED_POSITIONS,
    "per_frame": lib.PS_PREDICTION_PER_FRAME,
}

#: Interpolations of keyframed motion (``ps_interpolation``): ``hold`` (a step), ``linear``,
#: ``smooth`` (smoothstep 3s² − 2s³, zero velocity at every key).
INTERPOLATIONS: Dict[str, int] = {
    "hold": lib.PS_INTERPOLATION_HOLD,
    "linear": lib.PS_INTERPOLATION_LINEAR,
    "smooth": lib.PS_INTERPOLATION_SMOOTH,
}

#: What a handle holds (``ps_support``): ``position`` (each vertex's prescribed coordinates,
#: the default) or ``rotation`` (the group turns with its script and translates freely along
#: the coordinates outside its axes).
SUPPORTS: Dict[str, int] = {
    "position": lib.PS_SUPPORT_POSITION,
    "rotation": lib.PS_SUPPORT_ROTATION,
}

#: What drives a simulation (``ps_sim_kind``): one level is ``direct``; several levels are
#: ``psq`` (quasistatic) or ``progressive_dynamics`` (dynamic: a progressive animation), and
#: on a solid's hierarchy ``volumetric_dynamics`` (dynamic: VPD, a progressive animation over
#: tet levels).
KINDS: Dict[str, int] = {
    "direct": lib.PS_SIM_DIRECT,
    "psq": lib.PS_SIM_PSQ,
    "progressive_dynamics": lib.PS_SIM_PROGRESSIVE_DYNAMICS,
    "volumetric_dynamics": lib.PS_SIM_VOLUMETRIC_DYNAMICS,
}

#: Kinds that are progressive animations (frames per level, :meth:`Simulation.frames`).
_ANIMATIONS = frozenset({"progressive_dynamics", "volumetric_dynamics"})

#: Load distributions of :meth:`Simulation.add_load` (``ps_load_distribution``).
LOAD_DISTRIBUTIONS: Dict[str, int] = {
    "mass": lib.PS_LOAD_BY_MASS,
    "area": lib.PS_LOAD_BY_AREA,
    "per_vertex": lib.PS_LOAD_PER_VERTEX,
}

_GROUPS = ("simulation_", "material_", "contact_", "solver_", "progressive_")

#: Keyword → ps_sim_def field, for the parameter-table fields (``time_step`` →
#: ``simulation_time_step``). Read from the compiled struct, so new table rows appear here.
_DEF_FIELDS: Dict[str, str] = {
    name.split("_", 1)[1]: name
    for name, _ in ffi.typeof("ps_sim_def").fields
    if name.startswith(_GROUPS)
}


#: Every name :meth:`Simulation.set_param` knows: the parameter table's ``group.name``
#: entries, ``gravity.x/y/z`` and ``pressure``.
def _parameter_names() -> Tuple[str, ...]:
    """Every name ps_sim_set_param accepts, as the library lists them (ps_param_info_get)."""
    info = ffi.new("ps_param_info*")
    names = []
    for index in range(lib.ps_param_count()):
        if lib.ps_param_info_get(index, info) == lib.PS_OK:
            names.append(ffi.string(info.name).decode("ascii"))
    return tuple(names)


PARAMETERS: Tuple[str, ...] = _parameter_names()


def _choice_table() -> Dict[str, Tuple[str, ...]]:
    """Every named option ps_sim_set_choice accepts with its values."""
    info = ffi.new("ps_choice_info*")
    table = {}
    for index in range(lib.ps_choice_count()):
        if lib.ps_choice_info_get(index, info) == lib.PS_OK:
            options = ffi.string(info.options).decode("ascii").split("|")
            table[ffi.string(info.name).decode("ascii")] = tuple(options)
    return table


#: Named options of :meth:`Simulation.set_choice` (the choice table, scene keys of the same
#: names) → their values.
CHOICES: Dict[str, Tuple[str, ...]] = _choice_table()

#: Keywords of :class:`Simulation` that set named options.
_CHOICE_KEYWORDS = {
    "bending_model": "material.bending_model",
    "prolongation": "progressive.prolongation",
    "proxy_hessian": "progressive.proxy_hessian",
    "preview_membrane": "progressive.preview_membrane",
}

#: Short names accepted by set_param/get_param: ``thickness`` → ``material.thickness``.
_ALIASES: Dict[str, str] = {
    short: field.replace("_", ".", 1) for short, field in _DEF_FIELDS.items()
}

_INTEGER_PARAMETERS = frozenset(
    field.replace("_", ".", 1)
    for field, kind in ffi.typeof("ps_sim_def").fields
    if field.startswith(_GROUPS) and kind.type.kind == "primitive" and "int" in kind.type.cname
)


@dataclass(frozen=True)
class RefinementStats:
    """How a level's start was built from the coarser level by safe refinement (PSQ §4.4;
    ``ps_refinement_stats``); all zeros for level 0 and for scenes without contact."""

    batches: int  #: colour batches of vertex splits
    splits: int  #: vertex splits over all batches
    random_directions: int  #: splits whose target direction was unsafe (PSQ Alg. 5)
    rounds: int  #: additive-CCD advancement rounds over all batches
    stopped_vertices: int  #: moving vertices stopped by contact before their target
    relaxed_vertices: int  #: stopped vertices relaxed locally (PSQ §4.4.3)
    relaxation_iterations: int  #: Newton iterations of those relaxations
    inside_pairs: int  #: contact pairs left within their offset, opened by later solves
    #: 1 − Σ‖x̂ − x‖ / Σ‖x̂ − x₀‖ over the moving vertices: 1 when all reached their targets
    reached: float
    min_gap: float  #: smallest gap d − ξ of contact pairs outside their offsets, m

    @classmethod
    def _from_native(cls, raw: Any) -> "RefinementStats":
        return cls(
            **{name: getattr(raw, name) for name, _ in ffi.typeof("ps_refinement_stats").fields}
        )


@dataclass(frozen=True)
class StrainCorrectionStats:
    """How a refined start was brought under its strain limits (PSQ §4.4.5;
    ``ps_strain_correction_stats``); all zeros for level 0 and for scenes without strain
    limits."""

    strained_faces: int  #: faces at or beyond their strain limit before the correction
    over_limit_faces: int  #: … after it (0: the start is strain-feasible)
    newton_iterations: int  #: Newton iterations of the correction
    moved_coarse_vertices: bool  #: the coarser level's vertices had to move too
    stretch_before: float  #: largest principal stretch of a limited face before it
    stretch_after: float  #: … after it

    @classmethod
    def _from_native(cls, raw: Any) -> "StrainCorrectionStats":
        fields = ffi.typeof("ps_strain_correction_stats").fields
        values = {name: getattr(raw, name) for name, _ in fields}
        values["moved_coarse_vertices"] = bool(values["moved_coarse_vertices"])
        return cls(**values)


@dataclass(frozen=True)
class LevelStats:
    """Statistics of one level, accumulated over every step taken at it (``ps_level_stats``)."""

    level: int  #: which level
    steps: int  #: steps taken at this level
    newton_iterations: int  #: total Newton iterations
    converged_steps: int  #: steps whose Newton solve met the tolerance
    seconds: float  #: wall time stepping at this level, s
    energy: float  #: incremental potential after the last step, J
    gradient_norm: float  #: ‖∇E‖ over free DOFs after the last step, N
    simulated_time: float  #: simulated time reached, s
    error_rms: (
        float  #: RMS distance to the converged finest solution / bbox diagonal (NaN until measured)
    )
    error_max: (
        float  #: max distance to the converged finest solution / bbox diagonal (NaN until measured)
    )
    settles: int  #: solves at a fixed time (:meth:`Simulation.settle`)
    equilibrium: bool  #: the last solve left an equilibrium (quasistatic; see ps_level_stats)
    refine_seconds: float  #: wall time refining the coarser level into this one, s
    refinement: RefinementStats  #: how the level's start was built
    #: contact pairs whose offset is still lowered after the last solve (where contact kept a
    #: split from opening fully); 0 normally
    reduced_offsets: int
    raised_limits: int  #: faces whose strain limit is still raised after the last solve
    #: obstacle vertices the level's contact meets (fewer on coarse levels with progressive
    #: obstacles, PSQ §4.6)
    obstacle_vertices: int
    obstacle_refinement: RefinementStats  #: how the progressive obstacles were refined into it
    #: CG iterations refining projected Newton steps (``max_cg_iterations`` > 0; never in the
    #: coarse levels' proxy solves)
    cg_iterations: int
    #: Newton steps the line search lengthened beyond a whole step (``line_search_extrapolation``)
    extrapolated_steps: int
    strain_correction: StrainCorrectionStats  #: how the refined start met its strain limits


@dataclass(frozen=True)
class DynamicLevelStats:
    """One computed level of a progressive animation (``ps_dynamic_level_stats``)."""

    level: int  #: which level
    vertices: int  #: of the level's mesh
    steps: int  #: steps animated at this level
    newton_iterations: int  #: over its steps
    converged_steps: int  #: steps whose Newton solve met the tolerance
    first_step: int  #: its frame 0 is the animation's frame first_step (a window)
    seconds: float  #: wall time of its steps, s


def _step_stats_dtype() -> np.dtype:
    """The numpy layout of ``ps_step_stats``, read from the compiled struct."""
    names, formats, offsets = [], [], []
    for name, field in ffi.typeof("ps_step_stats").fields:
        names.append(name)
        offsets.append(field.offset)
        if field.type.kind == "array":
            formats.append(("f8", (field.type.length,)))
        else:
            formats.append("i4" if "int" in field.type.cname else "f8")
    return np.dtype(
        {
            "names": names,
            "formats": formats,
            "offsets": offsets,
            "itemsize": ffi.sizeof("ps_step_stats"),
        }
    )


#: The numpy structured dtype of :meth:`Simulation.step_stats`, one record per step:
#: ``step`` (1-based: the step from frame step − 1 to frame step), ``newton_iterations``,
#: ``converged`` (1 if the Newton solve met the tolerance), ``time`` (s, after the step),
#: ``seconds`` (wall time), ``kinetic_energy`` (J), ``center_of_mass`` (3 floats, m),
#: ``com_deviation`` (m, how far the centre of mass moved away from the preview's since frame 0, PD Fig. 19), ``continuity``
#: (VPD App. C eq. 18, dimensionless), ``continuity_error`` (eq. 17, m) and ``consistency``
#: (eq. 19, m).
STEP_STATS_DTYPE: np.dtype = _step_stats_dtype()


@dataclass(frozen=True)
class HandleReaction:
    """What a handle's support applies to the shell (``ps_handle_reaction``)."""

    force: np.ndarray  #: float64 (3,), N; 0 along the coordinates the handle leaves free
    moment: np.ndarray  #: float64 (3,), N·m about ``point``
    point: np.ndarray  #: float64 (3,), m, the centroid of the handle's vertices


def _handle_axes(axes: str, allow_none: bool = False) -> int:
    """``ps_axis`` bits of a string of distinct letters from ``"xyz"`` (``""`` only where
    ``allow_none``)."""
    if not isinstance(axes, str) or (not axes and not allow_none) or len(set(axes)) != len(axes):
        raise InvalidArgumentError(f"axes must be distinct letters from 'xyz', got {axes!r}")
    bits = 0
    for letter in axes:
        if letter not in "xyz":
            raise InvalidArgumentError(f"axes must be distinct letters from 'xyz', got {axes!r}")
        bits |= 1 << "xyz".index(letter)
    return bits


@dataclass(frozen=True)
class Frame:
    """One frame of a level of a progressive animation (see :meth:`Simulation.frames`)."""

    level: int  #: which level
    index: int  #: 0 = the initial state, k = after step k
    positions: np.ndarray  #: float64 (n, 3), m
    velocities: np.ndarray  #: float64 (n, 3), m/s


def _choice(table: Dict[str, int], value: str, what: str) -> int:
    """The C value of a named option, or :class:`InvalidArgumentError` listing the names."""
    if value not in table:
        raise InvalidArgumentError(f"unknown {what} {value!r}; the {what}s are {', '.join(table)}")
    return table[value]


def _name_of(table: Dict[str, int], value: int) -> str:
    return next(name for name, code in table.items() if code == value)


def _effect_bit(name: str) -> int:
    try:
        return EFFECTS[name]
    except (KeyError, TypeError):
        raise InvalidArgumentError(
            f"unknown effect {name!r}; the effects are {', '.join(EFFECTS)}"
        ) from None


def _effect_bits(effects: Union[str, Iterable[str]]) -> int:
    if isinstance(effects, str):
        effects = (effects,)
    bits = 0
    for name in effects:
        bits |= _effect_bit(name)
    return bits


def _real_rows(value: Any, name: str, shape: Tuple[int, ...], layout: str) -> np.ndarray:
    """``value`` as a C-contiguous float64 array of shape (k, *shape) with k >= 1.

    ``layout`` names the columns for the error message.
    """
    try:
        array = np.ascontiguousarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InvalidArgumentError(f"{name} must be real numbers, got {value!r}") from None
    if array.shape[1:] != shape or array.ndim != len(shape) + 1 or array.shape[0] == 0:
        wanted = ", ".join(["k"] + [str(n) for n in shape])
        raise InvalidArgumentError(
            f"{name} must have shape ({wanted}) with k >= 1 ({layout}), got {array.shape}"
        )
    return array


def _wind_keyframes(value: Any) -> np.ndarray:
    """Wind keyframes as a C-contiguous float64 (k, 4) array: time, wx, wy, wz."""
    return _real_rows(value, "wind_keyframes", (4,), "time, wx, wy, wz")


def _keyframe_rows(
    times: Any, translations: Any, axes: Optional[Any], angles: Optional[Any]
) -> np.ndarray:
    """Motion keyframes as the C-contiguous (k, 8) rows of ps_sim_set_handle_keyframes()."""
    time = _real_rows(times, "times", (), "one time per key, s")
    count = time.shape[0]
    translation = _real_rows(translations, "translations", (3,), "tx, ty, tz per key, m")
    axis = np.tile([0.0, 0.0, 1.0], (count, 1)) if axes is None else axes
    axis = _real_rows(axis, "axes", (3,), "ax, ay, az per key")
    angle = _real_rows(np.zeros(count) if angles is None else angles, "angles", (), "rad per key")
    for name, array in (("translations", translation), ("axes", axis), ("angles", angle)):
        if array.shape[0] != count:
            raise InvalidArgumentError(
                f"{name} has {array.shape[0]} keys, times has {count}: give one per key"
            )
    return np.ascontiguousarray(np.column_stack([time, translation, axis, angle]))


def _ascii(text: str, what: str) -> bytes:
    """``text`` as the C string of an option name or value."""
    if not isinstance(text, str):
        raise InvalidArgumentError(f"{what} must be a str, got {text!r}")
    try:
        return text.encode("ascii")
    except UnicodeEncodeError:
        raise InvalidArgumentError(f"{what} {text!r} is not ASCII") from None


def _parameter_name(name: str) -> bytes:
    if not isinstance(name, str):
        raise InvalidArgumentError(f"a parameter name must be a str, got {name!r}")
    return _ALIASES.get(name, name).encode("utf-8")


def _integer_field(value: Any, name: str) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    return int32_value(value, name)


class Simulation(NativeObject):
    """A progressive simulation: preview steps at the current level, then refinement.

    Create one on a :class:`Hierarchy` with keyword parameters (SI units), or from a JSON
    scene (:meth:`from_scene`, :meth:`from_scene_file`). The simulation keeps its hierarchy
    alive. It is a context manager; :meth:`close` releases it (closing twice is harmless,
    using a closed simulation raises :class:`~progsim.ClosedError`).

    Level arguments accept negative values counted from the finest level (``-1``).
    """

    _last_error_fn = staticmethod(lib.ps_sim_last_error)

    def __init__(
        self,
        hierarchy: Hierarchy,
        *,
        time_step: Optional[float] = None,
        duration: Optional[float] = None,
        output_every: Optional[int] = None,
        gravity_ramp: Optional[float] = None,
        youngs_modulus: Optional[float] = None,
        bending_youngs_modulus: Optional[float] = None,
        poisson_ratio: Optional[float] = None,
        thickness: Optional[float] = None,
        density: Optional[float] = None,
        friction: Optional[float] = None,
        strain_limit: Optional[float] = None,
        dhat: Optional[float] = None,
        contact_stiffness: Optional[float] = None,
        friction_velocity: Optional[float] = None,
        newton_tolerance: Optional[float] = None,
        max_newton_iterations: Optional[int] = None,
        max_cg_iterations: Optional[int] = None,
        line_search_extrapolation: Optional[bool] = None,
        crossing_start: Optional[bool] = None,
        consistency_weight: Optional[float] = None,
        galerkin_refresh: Optional[float] = None,
        preview_iterations: Optional[int] = None,
        preview_tolerance: Optional[float] = None,
        proximal: Optional[bool] = None,
        mode: str = "dynamic",
        prediction: Optional[str] = None,
        effects: Optional[Iterable[str]] = None,
        gravity: Optional[Sequence[float]] = None,
        pressure: Optional[float] = None,
        pinned: Optional[Sequence[int]] = None,
        wind: Optional[Sequence[float]] = None,
        wind_keyframes: Optional[Any] = None,
        wind_density: Optional[float] = None,
        wind_drag: Optional[float] = None,
        wind_lift: Optional[float] = None,
        bending_model: Optional[str] = None,
        prolongation: Optional[str] = None,
        proxy_hessian: Optional[str] = None,
        preview_membrane: Optional[str] = None,
    ) -> None:
        """Creates a simulation of ``hierarchy``, at rest on level 0.

        Its :attr:`kind` follows from the hierarchy and the mode: one level gives a direct
        simulation; several levels give a progressive animation (Progressive Dynamics) in
        ``"dynamic"`` mode, the default, and PSQ in ``"quasistatic"`` mode. On a solid's
        hierarchy (:attr:`Hierarchy.is_solid`) the body is the finest tet mesh
        (``youngs_modulus``, ``poisson_ratio`` and ``density`` its material); several levels
        animate it with VPD (``"volumetric_dynamics"``) in ``"dynamic"`` mode, while
        ``"quasistatic"`` mode and ``pinned`` need a single level.

        Every parameter left as None keeps the library default (``progsim params`` lists
        defaults and ranges).

        Args:
            hierarchy: the mesh hierarchy to simulate (kept alive by the simulation).
            time_step: s, in (0, 100]; default 0.01.
            duration: s, in (0, 1e7]; default 1 (used by CLI runs only).
            output_every: steps, >= 1; default 1 (used by CLI runs only).
            gravity_ramp: s, in [0, 1e7]; default 0. Gravity grows linearly from 0 over this
                time (quasistatic self-weight in load steps); 0: full gravity at once.
            youngs_modulus: Pa, in (0, 1e13]; default 1e6.
            bending_youngs_modulus: Pa, in [0, 1e13]; default 0: the bending term's own
                Young's modulus (0: ``youngs_modulus``).
            poisson_ratio: dimensionless, in (-1, 0.5); default 0.3.
            thickness: m, in (0, 10]; default 1e-3.
            density: kg/m³, in (0, 1e6]; default 200.
            friction: Coulomb μ of the shell's surface, in [0, 10]; default 0 (a contact pair
                uses √(μ_a μ_b); needs the ``friction`` effect).
            strain_limit: largest principal membrane stretch, 0 (none) or in (1, 100];
                default 0 (needs the ``strain_limit`` effect).
            dhat: m, the contact activation gap, in (0, 10]; default 1e-3.
            contact_stiffness: N/m³, the barrier stiffness κ, in [0, 1e30]; default 0
                (chosen from the loads and grown adaptively).
            friction_velocity: m/s, friction's smoothing speed ε_v, in (0, 1e3]; default 1e-3.
            newton_tolerance: dimensionless, in (0, 1]; default 1e-5.
            max_newton_iterations: >= 1; default 100.
            max_cg_iterations: >= 0; default 0 (off). CG iterations refining each projected
                Newton step against the exact Hessian (faster on soft twisting cloth, slower on
                stiff shells; see ``bench_newton_refinement``).
            line_search_extrapolation: default True. Lengthens whole Newton steps whose energy
                fell much more than predicted (doubling the step while the energy falls and
                CCD allows); False for comparison runs.
            crossing_start: default False. True lets a progressive simulation start from a
                finest rest shape that crosses itself (safe refinement separates it level by
                level); False refuses it with :class:`~progsim.IntersectingError` naming a
                crossing pair.
            consistency_weight: dimensionless, in [0, 1e12]; default 0 (off). A progressive
                animation's consistency penalty w/(2h²)‖x − P(x_coarser)‖²_M pulling each
                finer level toward the prolonged coarser frame (VPD eq. 4; 1 weighs it like
                the inertia).
            galerkin_refresh: mean finest edge lengths, in [0, 1e6]; default 0.5. A
                progressive animation's Galerkin proxy Hessian is reassembled once the finest
                state has moved this far (net of its mean translation) or Newton contracts
                slowly; 0: every Newton iteration.
            preview_iterations: >= 1; default 8. PSQ's Newton iterations per preview step on
                a coarse level (PSQ §4.5).
            preview_tolerance: dimensionless, in [0, 1]; default 0 (``newton_tolerance``).
                Tolerance of preview solves and of a preview level being at rest.
            proximal: default False. True adds PSQ eq. 1's proximal term to quasistatic steps
                on every level and in the direct baseline (keeps free bodies solvable).
            mode: ``"dynamic"`` (implicit Euler) or ``"quasistatic"`` (energy minimisation
                per load step).
            prediction: how a progressive animation's finer levels predict each step from
                the coarser frames, a :data:`PREDICTIONS` name; default ``"velocity_only"``.
            effects: names among ``membrane``, ``bending``, ``gravity``, ``pressure``,
                ``contact``, ``friction``, ``strain_limit``, ``wind``, ``elasticity``;
                default ``{"membrane", "bending", "gravity"}``, on a solid's hierarchy
                ``{"elasticity", "gravity"}`` (the library's defaults for each). A solid's
                effects must include ``elasticity`` and no shell effect (``membrane``,
                ``bending``, ``pressure``, ``strain_limit``, ``wind``).
            gravity: (gx, gy, gz), m/s²; default (0, -9.81, 0).
            pressure: Pa, applied when the ``pressure`` effect is on; default 0.
            pinned: finest-level vertex indices held still (they form handle 0).
            wind: (wx, wy, wz), m/s, the steady wind of the ``wind`` effect (dynamic only);
                default (0, 0, 0), still air.
            wind_keyframes: gusts as rows (time s, wx, wy, wz m/s), shape (k, 4), times
                increasing; the wind is linear between them and held outside them. Replaces
                ``wind``.
            wind_density: air density, kg/m³, in (0, 1e4]; default 1.2.
            wind_drag: drag coefficient C_d of each face, in [0, 100]; default 1.2.
            wind_lift: lift coefficient C_L of each face, in [0, 100]; default 0 (no lift).
            bending_model, prolongation, proxy_hessian, preview_membrane: named options
                (:data:`CHOICES` ``material.bending_model``, ``progressive.prolongation``,
                ``progressive.proxy_hessian``, ``progressive.preview_membrane``), set with
                :meth:`set_choice` once created; default the table's.

        Raises:
            InvalidArgumentError: a value out of range, an unknown mode, effect or option.
            InvalidSceneError: a pinned vertex out of range; on a solid's hierarchy, effects
                without ``elasticity`` or with a shell effect (naming it).
            UnsupportedError: a solid's hierarchy of several levels in ``"quasistatic"`` mode
                or with ``pinned`` vertices.
            ClosedError: ``hierarchy`` is closed.
        """
        super().__init__()
        self._hierarchy: Optional[Hierarchy] = None
        if not isinstance(hierarchy, Hierarchy):
            raise InvalidArgumentError(f"hierarchy must be a progsim.Hierarchy, got {hierarchy!r}")
        definition = ffi.new("ps_sim_def*")
        lib.ps_sim_def_init(definition)
        values = {
            "time_step": time_step,
            "duration": duration,
            "output_every": output_every,
            "gravity_ramp": gravity_ramp,
            "youngs_modulus": youngs_modulus,
            "bending_youngs_modulus": bending_youngs_modulus,
            "poisson_ratio": poisson_ratio,
            "thickness": thickness,
            "density": density,
            "friction": friction,
            "strain_limit": strain_limit,
            "dhat": dhat,
            "stiffness": contact_stiffness,
            "friction_velocity": friction_velocity,
            "newton_tolerance": newton_tolerance,
            "max_newton_iterations": max_newton_iterations,
            "max_cg_iterations": max_cg_iterations,
            "line_search_extrapolation": line_search_extrapolation,
            "crossing_start": crossing_start,
            "consistency_weight": consistency_weight,
            "galerkin_refresh": galerkin_refresh,
            "preview_iterations": preview_iterations,
            "preview_tolerance": preview_tolerance,
            "proximal": proximal,
        }
        for keyword, value in values.items():
            if value is None:
                continue
            field = _DEF_FIELDS[keyword]
            if field.replace("_", ".", 1) in _INTEGER_PARAMETERS:
                value = _integer_field(value, keyword)
            else:
                value = real_value(value, keyword)
            setattr(definition, field, value)
        definition.mode = _choice(MODES, mode, "mode")
        if prediction is not None:
            definition.prediction = _choice(PREDICTIONS, prediction, "prediction")
        if effects is not None:
            definition.effects = _effect_bits(effects)
        elif hierarchy.is_solid:  # what ps_sim_create() gives a solid for a NULL def
            definition.effects = lib.PS_EFFECT_ELASTICITY | lib.PS_EFFECT_GRAVITY
        if gravity is not None:
            definition.gravity = three_floats(gravity, "gravity")
        if pressure is not None:
            definition.pressure = real_value(pressure, "pressure")
        if wind is not None:
            definition.wind_velocity = three_floats(wind, "wind")
        for keyword, value in (
            ("wind_density", wind_density),
            ("wind_drag", wind_drag),
            ("wind_lift", wind_lift),
        ):
            if value is not None:
                setattr(definition, keyword, real_value(value, keyword))
        keyframe_buffer = None
        if wind_keyframes is not None:
            keyframes = _wind_keyframes(wind_keyframes)
            keyframe_buffer = ffi.from_buffer("double[]", keyframes)
            definition.wind_keyframes = keyframe_buffer
            definition.num_wind_keyframes = keyframes.shape[0]
        pinned_buffer = None
        if pinned is not None:
            pinned_array = as_indices(pinned, "pinned", "(k,)")
            if pinned_array.size:
                pinned_buffer = ffi.from_buffer("int32_t[]", pinned_array)
                definition.pinned_vertices = pinned_buffer
                definition.num_pinned_vertices = pinned_array.size

        hierarchy_cdata = hierarchy._handle()
        out = ffi.new("ps_sim**")
        with hierarchy._lock:
            status = lib.ps_sim_create(hierarchy_cdata, definition, out)
        check_create(status)
        del pinned_buffer, keyframe_buffer

        # The destructor holds the native hierarchy, so it is freed only after this
        # simulation, whatever order the garbage collector or the caller picks.
        borrowers = hierarchy._borrowers
        borrowers.append(None)

        def destroy(pointer, _keep=hierarchy_cdata, _destroy=lib.ps_sim_destroy):
            _destroy(pointer)
            borrowers.pop()

        self._cdata = ffi.gc(out[0], destroy)
        self._hierarchy = hierarchy
        named = {
            "bending_model": bending_model,
            "prolongation": prolongation,
            "proxy_hessian": proxy_hessian,
            "preview_membrane": preview_membrane,
        }
        for keyword, value in named.items():
            if value is not None:
                self.set_choice(_CHOICE_KEYWORDS[keyword], value)

    @classmethod
    def from_scene(
        cls, scene: Union[str, bytes, Mapping[str, Any]], base_dir: Optional[PathLike] = None
    ) -> "Simulation":
        """Creates a simulation from a JSON scene (format: ``scenes/README.md``).

        The scene's bodies form the hierarchy, which the simulation owns (see
        :attr:`hierarchy`).

        Args:
            scene: the scene as JSON text (comments allowed) or as a dict.
            base_dir: folder that relative mesh paths start from (default: the current one).

        Raises:
            InvalidSceneError: unknown key, missing field or value out of range; the message
                gives the JSON path (e.g. ``efects``).
            InvalidMeshError, ProgsimIOError: a body's mesh is invalid or unreadable.
        """
        if isinstance(scene, os.PathLike):
            raise InvalidArgumentError(
                "from_scene() takes the scene's JSON text; use from_scene_file() for a path"
            )
        if isinstance(scene, Mapping):
            scene = json.dumps(scene)
        text = scene.encode("utf-8") if isinstance(scene, str) else bytes(scene)
        if b"\0" in text:
            raise InvalidArgumentError("the scene text contains a NUL character")
        out = ffi.new("ps_sim**")
        directory = ffi.NULL if base_dir is None else os.fsencode(base_dir)
        check_create(lib.ps_sim_create_from_scene(text, directory, out))
        return cls._owning(out[0])

    @classmethod
    def from_scene_file(cls, path: PathLike) -> "Simulation":
        """Creates a simulation from a JSON scene file; relative mesh paths start from the
        file's folder. Raises like :meth:`from_scene`, and :class:`ProgsimIOError` for an
        unreadable file."""
        out = ffi.new("ps_sim**")
        check_create(lib.ps_sim_create_from_scene_file(os.fsencode(path), out))
        return cls._owning(out[0])

    @classmethod
    def _owning(cls, pointer: "ffi.CData") -> "Simulation":
        self = cls.__new__(cls)
        NativeObject.__init__(self)
        self._cdata = ffi.gc(pointer, lib.ps_sim_destroy)
        self._hierarchy = None
        return self

    # -- structure --------------------------------------------------------------------------

    @property
    def hierarchy(self) -> Hierarchy:
        """The hierarchy this simulation runs on: the one it was created with, or (for scenes,
        or if that one was closed) a view valid while the simulation is open."""
        if self._hierarchy is not None and not self._hierarchy.closed:
            self._handle()
            return self._hierarchy
        out = ffi.new("const ps_hierarchy**")
        self._call(lib.ps_sim_hierarchy, out)
        return Hierarchy._borrowed(ffi.cast("ps_hierarchy*", out[0]), self)

    @property
    def kind(self) -> str:
        """What drives this simulation, a :data:`KINDS` name: ``"direct"`` (one level),
        ``"psq"`` (quasistatic levels), ``"progressive_dynamics"`` (an animation) or
        ``"volumetric_dynamics"`` (an animation of a solid, VPD)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_get_kind, out)
        return _name_of(KINDS, out[0])

    @property
    def num_levels(self) -> int:
        """Number of levels of the hierarchy."""
        return self.hierarchy.num_levels

    @property
    def current_level(self) -> int:
        """The level steps run on now (0 = coarsest)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_current_level, out)
        return int(out[0])

    def _level(self, level: Optional[int]) -> int:
        if level is None:
            return self.current_level
        level = int32_value(level, "level")
        if level < 0:
            counted = self.num_levels + level
            return counted if counted >= 0 else level
        return level

    @property
    def num_handles(self) -> int:
        """Number of handles (scripted vertex groups); ``pinned`` vertices form handle 0."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_num_handles, out)
        return int(out[0])

    # -- parameters ---------------------------------------------------------------------------

    def set_param(self, name: str, value: float) -> None:
        """Sets a numeric parameter between steps.

        Args:
            name: a parameter-table name such as ``"material.youngs_modulus"`` (Pa),
                ``"simulation.time_step"`` (s), ``"solver.newton_tolerance"``, or
                ``"gravity.x"``/``"gravity.y"``/``"gravity.z"`` (m/s²) or ``"pressure"``
                (Pa, all bodies); the short keyword names (``"thickness"``...) work too.
                :data:`PARAMETERS` lists them.
            value: the new value, in the parameter's unit.

        Raises:
            InvalidArgumentError: unknown name (the message lists the known ones) or value
                out of range (NaN included); the simulation is unchanged.
        """
        self._call(lib.ps_sim_set_param, _parameter_name(name), real_value(value, name))

    def get_param(self, name: str) -> Union[float, int]:
        """The value of a numeric parameter (names as in :meth:`set_param`); integer
        parameters come back as int."""
        key = _parameter_name(name)
        out = ffi.new("double*")
        self._call(lib.ps_sim_get_param, key, out)
        if key.decode() in _INTEGER_PARAMETERS:
            return int(out[0])
        return float(out[0])

    def set_choice(self, name: str, value: str) -> None:
        """Sets named option ``name`` (a :data:`CHOICES` key, e.g.
        ``"progressive.proxy_hessian"``) to ``value``, one of its values.

        Before the first step, settle or refinement the simulation is rebuilt with it (its
        kind follows ``"simulation.mode"``); later it applies between steps like
        :meth:`set_param` (``"progressive.prolongation"`` from the next level on).

        Raises:
            InvalidArgumentError: an unknown name or value (the message lists the known ones).
        """
        self._call(lib.ps_sim_set_choice, _ascii(name, "name"), _ascii(value, "value"))

    def choice(self, name: str) -> str:
        """The value of named option ``name`` (material options: the first body's).

        Raises:
            InvalidArgumentError: an unknown name.
        """
        out = ffi.new("char**")
        self._call(lib.ps_sim_get_choice, _ascii(name, "name"), out)
        return ffi.string(out[0]).decode("ascii")

    @property
    def gravity(self) -> Tuple[float, float, float]:
        """Gravity (gx, gy, gz), m/s²; settable."""
        x, y, z = (float(self.get_param(f"gravity.{axis}")) for axis in "xyz")
        return (x, y, z)

    @gravity.setter
    def gravity(self, value: Sequence[float]) -> None:
        components = three_floats(value, "gravity")
        old = self.gravity
        try:
            for axis, component in zip("xyz", components):
                self.set_param(f"gravity.{axis}", component)
        except Exception:
            for axis, component in zip("xyz", old):
                self.set_param(f"gravity.{axis}", component)
            raise

    @property
    def mode(self) -> str:
        """The stepping mode, ``"dynamic"`` or ``"quasistatic"``; assignable between steps
        (switching to quasistatic zeroes the velocities)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_get_mode, out)
        return _name_of(MODES, out[0])

    @mode.setter
    def mode(self, name: str) -> None:
        self._call(lib.ps_sim_set_mode, _choice(MODES, name, "mode"))

    @property
    def prediction(self) -> str:
        """How a progressive animation's finer levels predict their steps, a
        :data:`PREDICTIONS` name; assignable while the preview is open (a progressive
        animation refuses it once a finer level is computed: :meth:`restart` first)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_get_prediction, out)
        return _name_of(PREDICTIONS, out[0])

    @prediction.setter
    def prediction(self, name: str) -> None:
        self._call(lib.ps_sim_set_prediction, _choice(PREDICTIONS, name, "prediction"))

    def set_effect(self, name: str, enabled: bool = True) -> None:
        """Enables or disables one effect (``membrane``, ``bending``, ``gravity``,
        ``pressure``) between steps."""
        self._call(lib.ps_sim_set_effect, _effect_bit(name), 1 if enabled else 0)

    @property
    def effects(self) -> FrozenSet[str]:
        """The enabled effects' names; assign a set of names to enable exactly those."""
        out = ffi.new("uint32_t*")
        self._call(lib.ps_sim_get_effects, out)
        return frozenset(name for name, bit in EFFECTS.items() if out[0] & bit)

    @effects.setter
    def effects(self, names: Iterable[str]) -> None:
        wanted = _effect_bits(names)
        for name, bit in EFFECTS.items():  # enable first: never passes through "no effect"
            if wanted & bit:
                self.set_effect(name, True)
        for name, bit in EFFECTS.items():
            if not wanted & bit:
                self.set_effect(name, False)

    def set_handle_motion(
        self,
        handle: int,
        velocity: Optional[Sequence[float]] = None,
        axis: Optional[Sequence[float]] = None,
        center: Optional[Sequence[float]] = None,
        angular_velocity: float = 0.0,
        offset: Optional[Sequence[float]] = None,
    ) -> None:
        """Scripts handle ``handle`` from the next step on.

        Its vertices follow x(t) = c + R(ω t)(x̄ − c) + v t + offset, with t the simulated
        time and x̄ the rest position. Replaces keyframes (:meth:`set_handle_keyframes`).

        Args:
            handle: handle index, ``0 <= handle < num_handles``.
            velocity: v, m/s (default zero).
            axis: rotation axis (normalised; default +z).
            center: c, the rotation centre, m (default the origin).
            angular_velocity: ω, rad/s.
            offset: a translation, m (default zero).

        Raises:
            OutOfRangeError: no such handle.
            InvalidArgumentError: a zero or non-finite axis, a vector without 3 components.
        """
        self._set_motion(
            lib.ps_sim_set_handle_motion,
            handle,
            "handle",
            velocity,
            axis,
            center,
            angular_velocity,
            offset,
        )

    def _set_motion(self, setter, index, name, velocity, axis, center, angular_velocity, offset):
        self._call(
            setter,
            int32_value(index, name),
            vec3(velocity, "velocity"),
            vec3(axis, "axis"),
            vec3(center, "center"),
            real_value(angular_velocity, "angular_velocity"),
            vec3(offset, "offset"),
        )

    def set_handle_keyframes(
        self,
        handle: int,
        times: Any,
        translations: Any,
        axes: Optional[Any] = None,
        angles: Optional[Any] = None,
        interpolation: str = "linear",
    ) -> None:
        """Scripts handle ``handle`` by keyframes from the next step on.

        Its vertices follow x(t) = c + R(t)(x̄ − c) + T(t) + offset, with t the simulated time,
        x̄ the rest position, c and offset those of the handle's current motion
        (:meth:`set_handle_motion` or the scene's), and the pose (T, R) interpolated between
        the keys: translations componentwise; rotations about one axis by their angle (a
        segment may turn several times), about different axes by quaternion slerp. Before
        the first key its pose, after the last held. Replaces the velocity and angular
        velocity.

        Args:
            handle: handle index, ``0 <= handle < num_handles``.
            times: key times, s, shape (k,), strictly increasing, k >= 1.
            translations: T at each key, m, shape (k, 3).
            axes: rotation axis at each key (non-zero, need not be unit), shape (k, 3);
                default +z.
            angles: rotation about the axis through c at each key, rad, shape (k,);
                default 0.
            interpolation: an :data:`INTERPOLATIONS` name: ``"hold"``, ``"linear"``
                (default) or ``"smooth"``.

        Raises:
            OutOfRangeError: no such handle.
            InvalidArgumentError: arrays of the wrong shape or with NaN/Inf, a zero axis,
                times not strictly increasing (the message names the key), an unknown
                interpolation.
        """
        self._set_keyframes(
            lib.ps_sim_set_handle_keyframes,
            handle,
            "handle",
            times,
            translations,
            axes,
            angles,
            interpolation,
        )

    def _set_keyframes(self, setter, index, name, times, translations, axes, angles, interpolation):
        rows = _keyframe_rows(times, translations, axes, angles)
        self._call(
            setter,
            int32_value(index, name),
            ffi.from_buffer("double[]", rows),
            rows.shape[0],
            _choice(INTERPOLATIONS, interpolation, "interpolation"),
        )

    def set_handle_axes(self, handle: int, axes: str) -> None:
        """Makes handle ``handle`` prescribe only the coordinates in ``axes`` from the next
        step on (scene key ``handles[i].axes``); its vertices move freely along the others.

        Args:
            handle: handle index, ``0 <= handle < num_handles``.
            axes: distinct letters from ``"xyz"``: ``"xyz"`` a clamp (the default), ``"z"`` a
                roller held in height, free to slide in x and y.

        Raises:
            OutOfRangeError: no such handle.
            InvalidArgumentError: ``axes`` is empty or has letters other than x, y, z.
        """
        self._call(lib.ps_sim_set_handle_axes, int32_value(handle, "handle"), _handle_axes(axes))

    def set_handle_support(self, handle: int, support: str, axes: str = "") -> None:
        """Makes handle ``handle`` a ``support`` prescribing the coordinates in ``axes`` from
        the next step on (scene keys ``handles[i].support`` and ``handles[i].axes``).

        Args:
            handle: handle index, ``0 <= handle < num_handles``.
            support: ``"position"`` (each vertex's prescribed coordinates; ``axes`` non-empty)
                or ``"rotation"`` (the group turns with its script, held still by a static one,
                and translates freely along the coordinates outside ``axes``; two or more rows
                of vertices hold a slope; single-level simulations only).
            axes: distinct letters from ``"xyz"``; ``""`` (the default) only for a rotation
                support: a free translation.

        Raises:
            OutOfRangeError: no such handle.
            InvalidArgumentError: an unknown support or bad letters.
            InvalidSceneError: no axis on a position support.
            UnsupportedError: a rotation support on several levels.
        """
        self._call(
            lib.ps_sim_set_handle_support,
            int32_value(handle, "handle"),
            _choice(SUPPORTS, support, "support"),
            _handle_axes(axes, allow_none=True),
        )

    def handle_reaction(self, handle: int, level: Optional[int] = None) -> HandleReaction:
        """The force and moment handle ``handle``'s support applied after the last solve on
        ``level`` (default: the current one): ∂E/∂x at its prescribed coordinates, which in a
        quasistatic step balances the loads.

        Raises:
            OutOfRangeError: no such level or handle.
            WrongCallOrderError: no solve on the level yet, or it is a preview level (its proxy
                holds the finest handle vertices and reports no reaction).
        """
        out = ffi.new("ps_handle_reaction*")
        self._call(
            lib.ps_sim_get_handle_reaction,
            self._level(level),
            int32_value(handle, "handle"),
            out,
        )
        return HandleReaction(
            force=np.array(list(out.force), dtype=np.float64),
            moment=np.array(list(out.moment), dtype=np.float64),
            point=np.array(list(out.point), dtype=np.float64),
        )

    def add_handle(self, vertices: Any, body: int = 0) -> int:
        """Adds a handle: finest-level vertices of ``body`` held at rest until
        :meth:`set_handle_motion` or :meth:`set_handle_keyframes` scripts them (scene key
        ``handles``).

        This rebuilds the simulation, so it is only allowed before the first step, settle or
        refinement. On a hierarchy of several levels handle i must be the hierarchy's vertex
        group i (``Hierarchy(..., vertex_group_ids=...)``, or ``pinned=`` for group 0 alone):
        after ``Simulation(..., pinned=...)`` (group 0), each call adds the next group.

        Args:
            vertices: vertex indices within the body's mesh, shape (k,), k >= 1.
            body: index of the scene's body; default 0.

        Returns:
            The handle's index (:attr:`num_handles` − 1).

        Raises:
            InvalidSceneError: no vertices, a vertex or body out of range.
            WrongCallOrderError: the simulation has stepped.
            InvalidArgumentError: on several levels, vertices that are not a vertex group of the
                hierarchy.
        """
        indices, buffer = index_buffer(vertices, "vertices")
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_add_handle, int32_value(body, "body"), buffer, indices.size, out)
        return int(out[0])

    def add_handle_box(self, box_min: Any, box_max: Any, body: int = 0) -> int:
        """Adds a handle of the vertices of ``body`` inside the axis-aligned box
        ``[box_min, box_max]`` (m, boundary included; scene key ``handles`` with a ``box``),
        otherwise as :meth:`add_handle`.

        On a solid's hierarchy of several levels (VPD) every level holds the vertices its box
        holds there (the levels share no vertices).

        Args:
            box_min: the box's lower corner, 3 finite numbers (m).
            box_max: its upper corner, at or above ``box_min`` on every axis.
            body: index of the scene's body; default 0.

        Returns:
            The handle's index (:attr:`num_handles` − 1).

        Raises:
            InvalidArgumentError: a non-finite corner, or ``box_min`` above ``box_max``.
            InvalidSceneError: a body out of range, a box that holds no vertex of the body, or
                (VPD) none of some level's, naming it.
            WrongCallOrderError: the simulation has stepped.
        """
        lo, hi = vec3(box_min, "box_min"), vec3(box_max, "box_max")
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_add_handle_box, int32_value(body, "body"), lo, hi, out)
        return int(out[0])

    @property
    def num_obstacles(self) -> int:
        """Number of obstacles (:meth:`add_obstacle` and the scene's ``"obstacles"``)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_num_obstacles, out)
        return int(out[0])

    def add_obstacle(
        self, vertices: Any, faces: Any, *, friction: float = 0.0, progressive: bool = False
    ) -> int:
        """Adds a collision object: a triangle mesh moved rigidly by a script, not simulated
        (scene key ``obstacles``); static until :meth:`set_obstacle_motion` or
        :meth:`set_obstacle_keyframes`. Needs the ``"contact"`` effect. Like
        :meth:`add_handle`, only before the first step.

        Args:
            vertices: world positions at t = 0, m, shape (n, 3).
            faces: vertex indices, shape (m, 3).
            friction: Coulomb μ of its surface, in [0, 10]; default 0.
            progressive: True: coarse levels of a PSQ simulation meet a decimated copy,
                refined with the shell (PSQ §4.6).

        Returns:
            The obstacle's index (0, 1, ... in order of addition, after the scene's).

        Raises:
            InvalidMeshError: the mesh fails validation (names the first bad element).
            IntersectingError: it crosses the shell at t = 0 or comes within its contact
                offset.
            InvalidSceneError: no ``"contact"`` effect, friction out of range.
            WrongCallOrderError: the simulation has stepped.
        """
        vertex_array = as_vertices(vertices)
        face_array = as_faces(faces)
        definition = ffi.new("ps_obstacle_def*")
        lib.ps_obstacle_def_init(definition)
        definition.vertices = ffi.from_buffer("double[]", vertex_array)
        definition.num_vertices = vertex_array.shape[0]
        definition.faces = ffi.from_buffer("int32_t[]", face_array)
        definition.num_faces = face_array.shape[0]
        definition.friction = real_value(friction, "friction")
        definition.progressive = 1 if progressive else 0
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_add_obstacle, definition, out)
        return int(out[0])

    def set_obstacle_motion(
        self,
        obstacle: int,
        velocity: Optional[Sequence[float]] = None,
        axis: Optional[Sequence[float]] = None,
        center: Optional[Sequence[float]] = None,
        angular_velocity: float = 0.0,
        offset: Optional[Sequence[float]] = None,
    ) -> None:
        """As :meth:`set_handle_motion`, for obstacle ``obstacle`` (its rest positions are
        those at t = 0).

        Raises:
            OutOfRangeError: no such obstacle.
            InvalidArgumentError: a zero or non-finite axis, a vector without 3 components.
        """
        self._set_motion(
            lib.ps_sim_set_obstacle_motion,
            obstacle,
            "obstacle",
            velocity,
            axis,
            center,
            angular_velocity,
            offset,
        )

    def set_obstacle_keyframes(
        self,
        obstacle: int,
        times: Any,
        translations: Any,
        axes: Optional[Any] = None,
        angles: Optional[Any] = None,
        interpolation: str = "linear",
    ) -> None:
        """As :meth:`set_handle_keyframes`, for obstacle ``obstacle``; messages name
        ``obstacles[i].motion.keyframes[k]``.

        Raises:
            OutOfRangeError: no such obstacle.
            InvalidArgumentError: as :meth:`set_handle_keyframes`.
        """
        self._set_keyframes(
            lib.ps_sim_set_obstacle_keyframes,
            obstacle,
            "obstacle",
            times,
            translations,
            axes,
            angles,
            interpolation,
        )

    def set_ground(
        self,
        normal: Sequence[float] = (0.0, 1.0, 0.0),
        height: float = 0.0,
        friction: float = 0.0,
        enabled: bool = True,
    ) -> None:
        """Sets the analytic ground, the half-space n·x >= height (scene key ``ground``), or
        removes it (``enabled=False``). Needs the ``"contact"`` effect; allowed between steps.

        Args:
            normal: n, pointing to the free side (any length > 0); default +y.
            height: m, the plane's offset along n.
            friction: Coulomb μ, in [0, 10]; default 0.
            enabled: False removes the ground.

        Raises:
            InvalidArgumentError: a zero or non-finite normal, a non-finite height.
            InvalidSceneError: friction out of range, no ``"contact"`` effect.
            IntersectingError: the shell is not above the ground by its contact offset.
        """
        self._call(
            lib.ps_sim_set_ground,
            1 if enabled else 0,
            vec3(normal, "normal"),
            real_value(height, "height"),
            real_value(friction, "friction"),
        )

    @property
    def num_loads(self) -> int:
        """Number of point and line loads (:meth:`add_load` and the scene's ``"loads"``)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_num_loads, out)
        return int(out[0])

    def add_load(
        self,
        vertices: Any = None,
        *,
        box: Optional[Tuple[Any, Any]] = None,
        force: Optional[Sequence[float]] = None,
        distribution: str = "mass",
        moment: float = 0.0,
        moment_axis: Optional[Sequence[float]] = None,
        normal_force: float = 0.0,
        ramp: float = 0.0,
        body: int = 0,
    ) -> int:
        """Adds a point or line load on a vertex group from the next step on.

        The force and moment are fixed in direction and size (potential −Σ f_i·x_i), the normal
        force follows the surface; all grow linearly from 0 over ``ramp`` seconds of simulated
        time. Progressive simulations apply dead loads on the finest level's vertices, through
        the prolongation on coarse levels.

        Args:
            vertices: vertex indices within the body's mesh, shape (k,), k >= 1; or None with
                ``box``.
            box: ``(box_min, box_max)``, instead of ``vertices``: the body's vertices inside
                this axis-aligned box (m, boundary included). On VPD levels, which share no
                vertices, each level takes its own vertices inside it.
            force: (Fx, Fy, Fz), N: the total force, or the force on each vertex with
                ``distribution="per_vertex"``; default zero.
            distribution: ``"mass"`` (by lumped vertex mass, the default), ``"area"`` (by
                lumped vertex area) or ``"per_vertex"`` (the force on every vertex).
            moment: N·m; default 0. A couple of forces on the group (summing to zero) with this
                moment about ``moment_axis``, weighted like the force.
            moment_axis: direction of the moment (any length > 0); default +z.
            normal_force: N along the unit vertex normals (the faces' winding), spread like the
                force and turning with the surface (a follower load); default 0.
                Single-level simulations only.
            ramp: s, >= 0; default 0 (the full load at once).
            body: index of the scene's body; default 0.

        Returns:
            The load's index (0, 1, ... in order of addition).

        Raises:
            InvalidArgumentError: an unknown distribution, a vector without 3 components, both
                ``vertices`` and ``box`` (or neither), a box corner above the other.
            InvalidSceneError: no vertices, a box holding none, a vertex or body out of range, a
                non-finite value, a zero moment axis, a negative ramp, a group on one line along
                the moment's axis.
        """
        if (vertices is None) == (box is None):
            raise InvalidArgumentError("add_load: give the group as vertices or as a box, not both")
        definition = ffi.new("ps_load_def*")
        lib.ps_load_def_init(definition)
        definition.body = int32_value(body, "body")
        # the buffers the def points to stay alive in these locals until the call returns
        lo = hi = buffer = ffi.NULL
        if box is not None:
            lo, hi = vec3(box[0], "box[0]"), vec3(box[1], "box[1]")
            definition.box_min, definition.box_max = lo, hi
        else:
            indices = as_indices(vertices, "vertices", "(k,)")
            buffer = ffi.from_buffer("int32_t[]", indices) if indices.size else ffi.NULL
            definition.vertices = buffer
            definition.num_vertices = indices.size
        if force is not None:
            definition.force = three_floats(force, "force")
        definition.distribution = _choice(LOAD_DISTRIBUTIONS, distribution, "distribution")
        definition.moment = real_value(moment, "moment")
        if moment_axis is not None:
            definition.moment_axis = three_floats(moment_axis, "moment_axis")
        definition.normal_force = real_value(normal_force, "normal_force")
        definition.ramp = real_value(ramp, "ramp")
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_add_load, definition, out)
        return int(out[0])

    # -- stepping ------------------------------------------------------------------------------

    def _run(
        self,
        function,
        *args: Any,
        progress: ProgressArg,
        total: Optional[int] = None,
        phase: Optional[str] = None,
    ) -> None:
        """Runs a long call with the progress trampoline installed (see :class:`ProgressRun`)."""
        handle = self._handle()
        run = ProgressRun(progress, total, phase)
        user_data = ffi.new_handle(run)
        depth = getattr(_thread_state, "callback_depth", 0)
        with self._lock:
            try:
                status = lib.ps_sim_set_progress_callback(handle, lib._progsim_progress, user_data)
                if status == lib.PS_OK:
                    status = function(handle, *args)
                message = decode(lib.ps_sim_last_error(handle)) if status != lib.PS_OK else ""
            finally:
                lib.ps_sim_set_progress_callback(handle, ffi.NULL, ffi.NULL)
                _thread_state.callback_depth = depth
                run.close()
        run.reraise()  # an exception from the callback wins over the CancelledError it caused
        if status != lib.PS_OK:
            raise make_error(status, message)

    def step_preview(self, steps: int = 1, progress: ProgressArg = False) -> None:
        """Advances ``steps`` time steps at the current level.

        Newton trouble does not fail the call (see :meth:`level_stats`).

        Args:
            steps: number of steps, >= 1.
            progress: ``True`` for a tqdm progress bar, ``False`` for none, or a callable
                ``(done, total, phase) -> bool`` called after each step; a true result
                cancels. An exception raised by the callable cancels the call and is
                re-raised here. Ctrl-C cancels cleanly (KeyboardInterrupt after the last
                completed step).

        Raises:
            CancelledError: the callable asked to stop; the state is that of the last
                completed step.
            InvalidArgumentError: ``steps < 1``.
            NumericalError: the solver produced non-finite positions.
        """
        steps = int32_value(steps, "steps")
        self._run(
            lib.ps_sim_step_preview,
            steps,
            progress=progress,
            total=steps if steps >= 1 else None,
            phase="preview",
        )

    def refine(self, progress: ProgressArg = False) -> None:
        """Refines the current level l to l + 1 with the prolongation P^l_{l+1} (PSQ eq. 7),
        so that later steps run on the finer level (previews below the finest level).

        A progressive animation instead animates level l + 1 over every previewed step (PD
        eqs. 5–6), each step predicted from level l's frames (:attr:`prediction`); it
        reports progress after each step, so ``progress=True`` shows a bar counting them.

        Args:
            progress: as for :meth:`step_preview` (phase ``"refine"``).

        Raises:
            OutOfRangeError: already at the finest level (the state is unchanged).
            IntersectingError: with contact, no safe position was found for a vertex split
                (PSQ §4.4's safe expansion); the state is unchanged.
            WrongCallOrderError: a progressive animation with no preview step yet.
            CancelledError: the progress callable asked to stop; a progressive animation
                discards the level (nothing changed).
        """
        self._run(lib.ps_sim_refine, progress=progress)

    def refine_window(self, first_step: int, last_step: int, progress: ProgressArg = False) -> None:
        """Progressive animation only: animates the next level over the previewed steps
        ``first_step`` to ``last_step`` only, so that time windows of a long animation can be
        refined apart (:mod:`progsim.windows` does so on Dask) and joined.

        The level's frame 0 is the animation's frame ``first_step``
        (:attr:`DynamicLevelStats.first_step`): for 0 as :meth:`refine`, else the coarser
        frame refined by PSQ's safe refinement (PD §4.6's vertical warm start) with the
        prolonged velocities. A level that is a window cannot be refined further.

        Raises:
            InvalidArgumentError: not ``0 <= first_step < last_step <=`` the previewed steps,
                or not a progressive animation.
            WrongCallOrderError: no preview step yet, or the current level is a window.
            UnsupportedError: a window after frame 0 of a solid under contact.
            OutOfRangeError, IntersectingError, CancelledError: as :meth:`refine`.
        """
        first = int32_value(first_step, "first_step")
        last = int32_value(last_step, "last_step")
        self._run(lib.ps_sim_refine_window, first, last, progress=progress, phase="refine")

    def settle(self, max_solves: int = 100, progress: ProgressArg = False) -> bool:
        """Solves again at the current time and loads until the level is at equilibrium (a
        Newton solve meets the tolerance with every face under its own strain limit) or
        ``max_solves`` solves were made.

        Returns:
            Whether equilibrium was reached.

        Raises:
            InvalidArgumentError: ``max_solves < 1``.
            CancelledError: the progress callable asked to stop.
        """
        max_solves = int32_value(max_solves, "max_solves")
        reached = ffi.new("int32_t*")
        self._run(
            lib.ps_sim_settle,
            max_solves,
            reached,
            progress=progress,
            total=max_solves if max_solves >= 1 else None,
            phase="settle",
        )
        return bool(reached[0])

    # -- results ------------------------------------------------------------------------------

    def positions(
        self, level: Optional[int] = None, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Positions of ``level`` (default: the current one) as a float64 (n, 3) array, m.

        The current level gives the current state, a coarser level its state when it was
        refined, a finer level the current state prolonged to it.

        Args:
            out: optional C-contiguous float64 (n, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(
            self._call, lib.ps_sim_get_positions, (self._level(level),), np.float64, out
        )

    def write_mesh(self, level: Optional[int], path: PathLike) -> None:
        """Writes a level's current mesh (``None``: the current level) to ``path``; the
        extension picks the format (``.obj``, ``.off``, ``.ply``).

        Raises:
            ProgsimIOError: the file cannot be written.
            OutOfRangeError: the level does not exist.
        """
        self._call(lib.ps_sim_write_mesh, self._level(level), os.fsencode(path))

    def level_stats(self, level: Optional[int] = None) -> LevelStats:
        """Statistics of ``level`` (default: the current one); levels not visited yet report
        zeros and NaN errors.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        out = ffi.new("ps_level_stats*")
        self._call(lib.ps_sim_get_level_stats, self._level(level), out)
        return LevelStats(
            level=int(out.level),
            steps=int(out.steps),
            newton_iterations=int(out.newton_iterations),
            converged_steps=int(out.converged_steps),
            seconds=float(out.seconds),
            energy=float(out.energy),
            gradient_norm=float(out.gradient_norm),
            simulated_time=float(out.simulated_time),
            error_rms=float(out.error_rms),
            error_max=float(out.error_max),
            settles=int(out.settles),
            equilibrium=bool(out.equilibrium),
            refine_seconds=float(out.refine_seconds),
            refinement=RefinementStats._from_native(out.refinement),
            reduced_offsets=int(out.reduced_offsets),
            raised_limits=int(out.raised_limits),
            obstacle_vertices=int(out.obstacle_vertices),
            obstacle_refinement=RefinementStats._from_native(out.obstacle_refinement),
            cg_iterations=int(out.cg_iterations),
            extrapolated_steps=int(out.extrapolated_steps),
            strain_correction=StrainCorrectionStats._from_native(out.strain_correction),
        )

    # -- progressive animation ------------------------------------------------------------------

    def num_frames(self, level: int = 0) -> int:
        """Frames of a computed level of a progressive animation: previewed steps + 1 (frame
        0 is the initial state, frame k the state after step k).

        Raises:
            OutOfRangeError: the level does not exist or has not been computed.
            InvalidArgumentError: not a progressive animation (see :attr:`kind`).
        """
        out = ffi.new("int32_t*")
        self._call(lib.ps_sim_num_frames, self._level(level), out)
        return int(out[0])

    def frame_positions(
        self, level: int, frame: int, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Positions of frame ``frame`` of ``level`` as a float64 (n, 3) array, m.

        Args:
            level: a computed level (negative counts from the finest level).
            frame: 0 to :meth:`num_frames` − 1.
            out: optional C-contiguous float64 (n, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: a level or frame not computed.
            InvalidArgumentError: not a progressive animation, or a bad ``out``.
        """
        where = (self._level(level), int32_value(frame, "frame"))
        return fetch_rows(self._call, lib.ps_sim_get_frame_positions, where, np.float64, out)

    def frame_velocities(
        self, level: int, frame: int, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Velocities of frame ``frame`` of ``level`` as a float64 (n, 3) array, m/s; as
        :meth:`frame_positions`."""
        where = (self._level(level), int32_value(frame, "frame"))
        return fetch_rows(self._call, lib.ps_sim_get_frame_velocities, where, np.float64, out)

    def frames(self, level: int = 0) -> Iterator[Frame]:
        """Iterates over the frames of a computed level, from frame 0 (read from disk one at
        a time, so long animations do not fill memory).

        Raises:
            OutOfRangeError: the level does not exist or has not been computed.
        """
        level = self._level(level)
        for index in range(self.num_frames(level)):
            yield Frame(
                level,
                index,
                self.frame_positions(level, index),
                self.frame_velocities(level, index),
            )

    def set_preview_velocities(self, velocities: Any) -> None:
        """Sets the preview's initial velocities, a (n₀, 3) array (m/s, n₀ the vertices of
        level 0), before its first step.

        Raises:
            InvalidArgumentError: a wrong shape or a NaN/Inf entry.
            WrongCallOrderError: the preview has taken steps (:meth:`restart` first).
        """
        array = as_vertices(velocities, "velocities")
        buffer = ffi.from_buffer("double[]", array) if array.size else ffi.NULL
        self._call(lib.ps_sim_set_preview_velocities, buffer, array.size)

    def restart(self) -> None:
        """Discards every level's frames and starts the preview again at rest with the
        current parameters (initial velocities set before are discarded too)."""
        self._call(lib.ps_sim_restart)

    def step_stats(self, level: int = 0) -> np.ndarray:
        """Per-step statistics of a computed level as a numpy structured array of
        :data:`STEP_STATS_DTYPE`, one record per step in order (``stats["kinetic_energy"]``,
        ``stats["center_of_mass"]`` (steps, 3), ``stats["com_deviation"]``, ...).

        Raises:
            OutOfRangeError: the level does not exist or has not been computed.
        """
        level = self._level(level)
        count = ffi.new("size_t*")
        self._call(lib.ps_sim_get_step_stats, level, ffi.NULL, 0, count)
        stats = np.zeros(count[0], dtype=STEP_STATS_DTYPE)
        if count[0]:
            buffer = ffi.cast("ps_step_stats*", ffi.from_buffer(stats, require_writable=True))
            self._call(lib.ps_sim_get_step_stats, level, buffer, count[0], count)
        return stats

    def dynamic_level_stats(self, level: int = 0) -> DynamicLevelStats:
        """Size and work of a computed level of a progressive animation.

        Raises:
            OutOfRangeError: the level does not exist or has not been computed.
        """
        out = ffi.new("ps_dynamic_level_stats*")
        self._call(lib.ps_sim_get_dynamic_level_stats, self._level(level), out)
        fields = ffi.typeof("ps_dynamic_level_stats").fields
        return DynamicLevelStats(**{name: getattr(out, name) for name, _ in fields})

    def __repr__(self) -> str:
        if self.closed:
            return "<progsim.Simulation (closed)>"
        try:
            if self.kind in _ANIMATIONS:
                return (
                    f"<progsim.Simulation progressive animation, level {self.current_level} of "
                    f"{self.num_levels} computed, {self.num_frames(0)} frames>"
                )
            return (
                f"<progsim.Simulation level {self.current_level} of {self.num_levels}, "
                f"t = {self.level_stats().simulated_time:g} s>"
            )
        except Exception:  # noqa: BLE001 - repr must not fail (e.g. inside a callback)
            return "<progsim.Simulation>"
