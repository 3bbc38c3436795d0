"""Progressive simulation (PSQ) through Python: preview on the coarsest level, refinement to
the finest, errors of the coarse levels against the converged result, and the accuracy report."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import progsim

from conftest import MESH

TOP_ROW = list(range(420, 441))  # y = 1 in the bundled square cloth
PLATE = Path(__file__).resolve().parents[3] / "scenes" / "psq_plate_buckling.json"


@pytest.fixture()
def hanging():
    """A cloth hanging from its top row in its own plane: a stable equilibrium, 3 levels."""
    with progsim.Hierarchy.from_file(
        MESH, coarse_vertex_counts=[40, 120], pinned=TOP_ROW
    ) as hierarchy:
        with progsim.Simulation(
            hierarchy, mode="quasistatic", time_step=1.0, pinned=TOP_ROW
        ) as sim:
            yield sim


def test_preview_refine_and_converge(hanging):
    sim = hanging
    sim.step_preview(1)
    assert sim.settle(300)
    assert sim.current_level == 0
    preview = sim.positions(-1)  # the preview prolonged to the finest mesh
    assert preview.shape == (441, 3)
    stats = sim.level_stats(0)
    assert stats.steps == 1 and stats.equilibrium and math.isnan(stats.error_rms)
    sim.refine()
    assert sim.current_level == 1 and sim.settle(300)
    sim.refine()
    assert sim.settle(50)
    assert sim.level_stats(1).refine_seconds > 0.0
    # No contact: the prolonged state is the start, no safe expansion ran.
    assert sim.level_stats(1).refinement.splits == 0 and sim.level_stats(1).reduced_offsets == 0
    coarse = sim.level_stats(0)
    assert 0.0 < coarse.error_max < 0.05 and coarse.error_rms <= coarse.error_max
    assert sim.level_stats(2).error_max == 0.0
    rest = sim.hierarchy.rest_positions(-1)
    assert np.array_equal(sim.positions()[TOP_ROW], rest[TOP_ROW])  # the pins held
    assert sim.positions()[:, 1].min() < rest[:, 1].min()  # it stretched under gravity
    with pytest.raises(progsim.OutOfRangeError, match="finest"):
        sim.refine()


def test_refinement_with_contact_reports_its_splits():
    """With self-contact, refinement is PSQ §4.4's safe expansion; its statistics reach Python."""
    with progsim.Hierarchy.from_file(
        MESH, coarse_vertex_counts=[40, 120], pinned=TOP_ROW
    ) as hierarchy:
        effects = ["membrane", "bending", "gravity", "contact"]
        with progsim.Simulation(
            hierarchy, mode="quasistatic", time_step=1.0, pinned=TOP_ROW, effects=effects
        ) as sim:
            sim.step_preview(1)
            sim.refine()
            assert sim.settle(300)
            stats = sim.level_stats(1).refinement
            fine, coarse = (hierarchy.level_size(level)[0] for level in (1, 0))
            assert stats.splits == fine - coarse and stats.batches >= 1
            assert 0.0 < stats.reached <= 1.0 and stats.min_gap > 0.0
            assert isinstance(stats, progsim.RefinementStats)


def test_refined_start_is_brought_under_its_strain_limit():
    """The bundled drape at 21 × 21 vertices: refinement stretches faces far beyond the cloth's
    strain limit of 1.06; the strain correction (PSQ §4.4.5) brings every one back under it."""
    scenes = Path(__file__).resolve().parents[3] / "scenes"
    text = (scenes / "psq_cloth_on_sphere.json").read_text()
    assert '"nx": 40, "ny": 40' in text
    text = text.replace('"nx": 40, "ny": 40', '"nx": 20, "ny": 20')
    with progsim.Simulation.from_scene(text, scenes) as sim:
        sim.step_preview(4)
        assert sim.settle(300)
        sim.refine()
        coarse, fine = sim.level_stats(0), sim.level_stats(1)
    assert coarse.strain_correction == progsim.StrainCorrectionStats(0, 0, 0, False, 0.0, 0.0)
    correction = fine.strain_correction
    assert correction.strained_faces > 0 and correction.over_limit_faces == 0
    assert correction.stretch_before > 1.06 > correction.stretch_after
    assert correction.newton_iterations > 0


def _preview_then_refine_once(sim, steps):
    """On a two-level scene: preview steps, equilibrium on the coarse level, refinement,
    equilibrium on the finest; returns the two levels' statistics."""
    sim.step_preview(steps)
    assert sim.settle(300)
    sim.refine()
    assert sim.settle(300)
    return sim.level_stats(0), sim.level_stats(1)


def test_progressive_obstacle_statistics():
    """A progressive sphere (PSQ §4.6): decimated on the coarse level, refined with the cloth."""
    scene = Path(__file__).resolve().parents[3] / "tests" / "data" / "progressive_obstacle.json"
    with progsim.Simulation.from_scene_file(scene) as sim:
        coarse, fine = _preview_then_refine_once(sim, 1)
        assert fine.obstacle_vertices == 162  # the sphere's own vertices
        assert 0 < coarse.obstacle_vertices < fine.obstacle_vertices
        assert coarse.obstacle_refinement.splits == 0
        assert fine.obstacle_refinement.splits == fine.obstacle_vertices - coarse.obstacle_vertices
        assert 0.0 < fine.obstacle_refinement.reached <= 1.0


def test_cg_refinement_counts_only_on_the_finest_level(hanging):
    """solver.max_cg_iterations from a scene: the coarse proxy never refines, the wrung finest
    level does."""
    scene = Path(__file__).resolve().parents[3] / "tests" / "data" / "twist_cg_refined.json"
    with progsim.Simulation.from_scene_file(scene) as sim:
        assert sim.get_param("solver.max_cg_iterations") == 50
        coarse, fine = _preview_then_refine_once(sim, 6)
        assert coarse.newton_iterations > 0 and coarse.cg_iterations == 0
        assert fine.newton_iterations > 0 and fine.cg_iterations > 0
    assert hanging.get_param("solver.max_cg_iterations") == 0  # opt-in
    with pytest.raises(progsim.InvalidArgumentError, match="max_cg_iterations"):
        progsim.Simulation(hanging.hierarchy, max_cg_iterations=-1)


def _extrapolated_preview_steps(on):
    """Newton steps the line search lengthened on the twist's coarse level over 6 previews."""
    scene = Path(__file__).resolve().parents[3] / "tests" / "data" / "twist_cg_refined.json"
    with progsim.Simulation.from_scene_file(scene) as sim:
        assert sim.get_param("solver.line_search_extrapolation") == 1  # on by default
        sim.set_param("solver.line_search_extrapolation", on)
        sim.step_preview(6)
        return sim.level_stats(0).extrapolated_steps


def test_line_search_extrapolation_switch(hanging):
    """solver.line_search_extrapolation: on, some of the twist's coarse steps are lengthened;
    off, none; the constructor takes it and refuses values other than 0 and 1."""
    assert _extrapolated_preview_steps(1) > 0
    assert _extrapolated_preview_steps(0) == 0
    with progsim.Simulation(
        hanging.hierarchy,
        mode="quasistatic",
        time_step=1.0,
        pinned=TOP_ROW,
        line_search_extrapolation=False,
    ) as sim:
        assert sim.get_param("solver.line_search_extrapolation") == 0
    with pytest.raises(progsim.InvalidArgumentError, match="line_search_extrapolation"):
        progsim.Simulation(hanging.hierarchy, line_search_extrapolation=2)


def test_pins_must_be_the_hierarchys(hanging):
    with pytest.raises(progsim.InvalidArgumentError, match="pinned_vertices"):
        progsim.Simulation(
            hanging.hierarchy, mode="quasistatic", time_step=1.0, pinned=TOP_ROW[:-1]
        )


def test_settle_rejects_nonsense(hanging):
    with pytest.raises(progsim.InvalidArgumentError, match="max_solves"):
        hanging.settle(0)


def test_accuracy_report(tmp_path):
    phases = []
    with progsim.Accuracy(
        PLATE, progress=lambda done, total, phase: phases.append(phase) and False
    ) as report:
        assert [(row.method, row.level) for row in report.rows] == [
            ("progressive", 0),
            ("progressive", 1),
            ("progressive", 2),
            ("direct", 0),
            ("direct", 1),
            ("direct", 2),
        ]
        assert report.rows[2].error_max == 0.0  # the reference itself
        assert report.rows[0].seconds < report.rows[2].seconds
        assert all(row.vertices > 0 and row.newton_iterations > 0 for row in report.rows)
        assert all(row.intersecting_pairs == 0 and row.converged for row in report.rows)
        assert all(row.load_steps == 10 and row.finished for row in report.rows)
        report.write(tmp_path / "plate")
    assert "progressive level 1" in phases and "direct level 2" in phases
    assert "direct level 2, load step 10 of 10" in phases
    written = sorted(p.name for p in (tmp_path / "plate").iterdir())
    assert written == [
        "accuracy.csv",
        "accuracy.md",
        "error_by_level.png",
        "error_vs_time.png",
        "time_by_level.png",
    ]
    assert (tmp_path / "plate" / "error_vs_time.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_accuracy_needs_coarse_levels(tmp_path):
    scene = tmp_path / "flat.json"
    scene.write_text(
        '{"effects": ["membrane"], "bodies": [{"name": "s", "mesh": '
        '{"generator": "grid", "width": 1, "height": 1, "nx": 2, "ny": 2}}]}'
    )
    with pytest.raises(progsim.InvalidSceneError, match="coarse levels"):
        progsim.Accuracy(scene)


def test_accuracy_solves_directly_only_the_levels_asked_for_within_the_time_ratio(capsys):
    with progsim.Accuracy(
        PLATE, direct_levels=[2, 0], direct_time_ratio=1e-9, progress=True
    ) as report:
        assert [(row.method, row.level) for row in report.rows][3:] == [
            ("direct", 2),
            ("direct", 0),
        ]
        for row in report.rows[3:]:
            assert not row.finished and not row.converged and row.load_steps < 10
        assert all(row.finished for row in report.rows[:3])
        # The limit is the ratio times the progressive time to the converged finest level.
        assert report.direct_time_limit == 1e-9 * report.rows[2].seconds
    err = capsys.readouterr().err
    # One bar over the whole run (relabelled per phase and load step), left at 100 %.
    assert err.count("\n") == 1 and "100/100" in err, err


def test_accuracy_time_ratio_of_the_preview_gives_the_direct_solve_that_many_previews():
    with progsim.Accuracy(
        PLATE, direct_levels=[2], direct_time_ratio=2.0, direct_time_of_preview=True
    ) as report:
        preview = report.rows[0]
        assert (preview.method, preview.level) == ("progressive", 0)
        assert report.direct_time_limit == 2.0 * preview.seconds
    with progsim.Accuracy(PLATE, direct_levels=[0]) as unlimited:
        assert unlimited.direct_time_limit == 0.0


@pytest.mark.parametrize(
    "keywords, error, match",
    [
        ({"direct_levels": [3]}, progsim.InvalidArgumentError, "direct level 3 does not exist"),
        ({"direct_time_ratio": -1.0}, progsim.InvalidArgumentError, "time ratio"),
        ({"direct_time_ratio": "fast"}, progsim.InvalidArgumentError, "real number"),
        ({"direct_levels": [[0]]}, progsim.InvalidArgumentError, "1-D"),
    ],
)
def test_accuracy_refuses_direct_solves_that_make_no_sense(keywords, error, match):
    with pytest.raises(error, match=match):
        progsim.Accuracy(PLATE, **keywords)


CROSSING = Path(__file__).resolve().parents[3] / "tests" / "data" / "crossing_flap"


def test_a_crossing_input_is_refused_unless_the_scene_opts_in():
    """Issue 28's one rule: a finest mesh that crosses itself, with contact on, is refused naming
    a crossing pair of the input, from a scene file and from code; crossing_start lets it run."""
    with pytest.raises(progsim.IntersectingError, match="the input mesh: shell face"):
        progsim.Simulation.from_scene_file(CROSSING.with_suffix(".json"))
    with progsim.Hierarchy.from_file(
        CROSSING.with_suffix(".obj"), coarse_vertex_counts=[40, 100]
    ) as hierarchy:
        options = dict(mode="quasistatic", time_step=1.0, effects={"membrane", "contact"})
        with pytest.raises(progsim.IntersectingError, match="the input mesh: shell face"):
            progsim.Simulation(hierarchy, **options)
        with progsim.Simulation(hierarchy, crossing_start=True, **options) as sim:
            assert sim.get_param("contact.crossing_start") == 1


def test_hierarchy_contact_offset_is_checked():
    """ps_hierarchy_def.contact_offset: a length >= 0 (the levels keep it; C++ tests measure)."""
    with pytest.raises(progsim.InvalidArgumentError, match="contact_offset"):
        progsim.Hierarchy.from_file(
            CROSSING.with_suffix(".obj"), coarse_vertex_counts=[40], contact_offset=-1e-3
        )
    with progsim.Hierarchy.from_file(
        CROSSING.with_suffix(".obj"), coarse_vertex_counts=[40], contact_offset=2.5e-4
    ) as hierarchy:
        assert hierarchy.num_levels == 2


def test_preview_settings_from_keywords_cap_the_preview():
    """preview_iterations, preview_tolerance and proximal reach the core through ps_sim_def."""
    with progsim.Hierarchy.from_file(
        MESH, coarse_vertex_counts=[40, 120], pinned=TOP_ROW
    ) as hierarchy:
        with progsim.Simulation(
            hierarchy,
            mode="quasistatic",
            time_step=1.0,
            pinned=TOP_ROW,
            preview_iterations=1,
            preview_tolerance=1e-4,
            proximal=True,
        ) as sim:
            assert sim.get_param("preview_iterations") == 1
            assert sim.get_param("preview_tolerance") == 1e-4
            assert sim.get_param("proximal") == 1
            sim.step_preview(3)
            assert sim.level_stats(0).newton_iterations <= 3  # one per preview step
            sim.set_param("preview_iterations", 8)
            assert sim.get_param("progressive.preview_iterations") == 8
            with pytest.raises(progsim.InvalidArgumentError, match="preview_iterations"):
                sim.set_param("preview_iterations", 0)
