"""Closing, context managers, garbage collection and threads never crash."""

from __future__ import annotations

import gc
import subprocess
import sys
import textwrap
import threading
import weakref

import numpy as np
import pytest

import progsim
from conftest import MESH, grid


def test_close_twice_is_safe():
    hierarchy = progsim.Hierarchy(*grid())
    sim = progsim.Simulation(hierarchy)
    sim.close()
    sim.close()
    hierarchy.close()
    hierarchy.close()
    assert sim.closed and hierarchy.closed
    assert "closed" in repr(sim) and "closed" in repr(hierarchy)


def test_closed_objects_raise_a_clear_error():
    hierarchy = progsim.Hierarchy(*grid())
    sim = progsim.Simulation(hierarchy)
    sim.close()
    for call in (
        lambda: sim.step_preview(1),
        lambda: sim.positions(),
        lambda: sim.set_param("material.thickness", 1e-3),
        lambda: sim.level_stats(),
        lambda: sim.refine(),
        lambda: sim.hierarchy,
        lambda: sim.effects,
    ):
        with pytest.raises(progsim.ClosedError, match="Simulation is closed") as raised:
            call()
        assert (
            isinstance(raised.value, ValueError) and raised.value.status == "PS_ERROR_NULL_ARGUMENT"
        )
    hierarchy.close()
    with pytest.raises(progsim.ClosedError, match="Hierarchy is closed"):
        hierarchy.num_levels
    with pytest.raises(progsim.ClosedError, match="Hierarchy is closed"):
        progsim.Simulation(hierarchy)


def test_context_managers_close():
    with progsim.Hierarchy(*grid()) as hierarchy:
        with progsim.Simulation(hierarchy) as sim:
            sim.step_preview(1)
        assert sim.closed and not hierarchy.closed
    assert hierarchy.closed


def test_simulation_outlives_its_closed_hierarchy():
    vertices, faces = grid()
    with progsim.Hierarchy(vertices, faces) as hierarchy:
        sim = progsim.Simulation(hierarchy, pinned=[6, 8], gravity=(0, 0, -9.81))
    assert hierarchy.closed
    # The native hierarchy lives on for the simulation; its view is still readable.
    sim.step_preview(2)
    assert sim.positions()[:, 2].min() < 0
    np.testing.assert_array_equal(sim.hierarchy.faces(), faces)
    sim.close()


def test_gc_of_simulation_after_hierarchy_variable_deleted():
    hierarchy = progsim.Hierarchy(*grid())
    hierarchy_ref = weakref.ref(hierarchy)
    sim = progsim.Simulation(hierarchy, gravity=(0, 0, -9.81))
    del hierarchy
    gc.collect()
    assert hierarchy_ref() is not None  # kept alive by the simulation
    sim.step_preview(2)
    assert sim.hierarchy.level_size() == (9, 8)
    assert sim.positions()[:, 2].min() < 0
    sim_ref = weakref.ref(sim)
    del sim
    gc.collect()
    assert sim_ref() is None and hierarchy_ref() is None  # both freed, no leak


def test_gc_in_a_reference_cycle():
    hierarchy = progsim.Hierarchy(*grid())
    sim = progsim.Simulation(hierarchy)
    sim.cycle = sim  # only the cyclic collector can free it
    hierarchy.cycle = sim
    refs = weakref.ref(sim), weakref.ref(hierarchy)
    del sim, hierarchy
    gc.collect()
    assert all(ref() is None for ref in refs)


def test_interpreter_exit_without_closing(tmp_path):
    # Objects left for interpreter shutdown, in both creation orders and in a cycle.
    script = textwrap.dedent(f"""
        import progsim
        h = progsim.Hierarchy.from_file({str(MESH)!r})
        s1 = progsim.Simulation(h, pinned=[420])
        s2 = progsim.Simulation(h)
        s2.me = s2
        s1.step_preview(1)
        scene = progsim.Simulation.from_scene_file({str(MESH.parents[1] / "hanging_cloth.json")!r})
        view = scene.hierarchy
        del scene  # the view keeps the simulation alive
        h.close()
        print("ok", view.num_levels)
        """)
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "ok 1"


def test_simulations_on_threads_share_a_hierarchy():
    with progsim.Hierarchy(*grid(3, 3)) as hierarchy:
        sims = [progsim.Simulation(hierarchy, gravity=(0, 0, -9.81), pinned=[0]) for _ in range(2)]
        errors = []

        def run(sim):
            try:
                sim.step_preview(3)
            except BaseException as error:  # noqa: B902
                errors.append(error)

        threads = [threading.Thread(target=run, args=(sim,)) for sim in sims]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        assert not errors
        np.testing.assert_array_equal(sims[0].positions(), sims[1].positions())
        assert sims[0].level_stats().steps == 3
        for sim in sims:
            sim.close()
