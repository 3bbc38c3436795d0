"""Handles, obstacles and the ground from Python: a scene built in code equals the same scene
read from JSON, step by step, bit for bit; a progressive obstacle on a PSQ hierarchy; bad
objects are refused naming the problem, with nothing changed."""

import numpy as np
import pytest

import progsim

PLATE = np.array([[0.1, 0.1, -0.03], [0.3, 0.1, -0.03], [0.3, 0.3, -0.03], [0.1, 0.3, -0.03]])
PLATE_FACES = np.array([[0, 1, 2], [0, 2, 3]])
EFFECTS = ["membrane", "bending", "gravity", "contact", "friction"]


def _scene(plate_file: str) -> dict:
    """A 0.4 m sheet (vertex (i, j) at 5 j + i) falling in -z onto a rising plate, two corners
    lifted by smooth keys, a third rising at 0.1 m/s, a frictional ground below."""
    return {
        "simulation": {"time_step": 0.01},
        "gravity": [0, 0, -9.81],
        "effects": EFFECTS,
        "bodies": [{"mesh": {"generator": "grid", "width": 0.4, "height": 0.4, "nx": 4, "ny": 4}}],
        "handles": [
            {
                "body": 0,
                "vertices": [0, 4],
                "motion": {
                    "interpolation": "smooth",
                    "keyframes": [{"time": 0}, {"time": 0.1, "translation": [0, 0, 0.02]}],
                },
            },
            {"body": 0, "vertices": [24], "motion": {"velocity": [0, 0, 0.1]}},
        ],
        "obstacles": [
            {
                "mesh": {"file": plate_file},
                "friction": 0.2,
                "motion": {"keyframes": [{"time": 0}, {"time": 0.1, "translation": [0, 0, 0.01]}]},
            }
        ],
        "ground": {"normal": [0, 0, 2], "height": -0.1, "friction": 0.3},
    }


def _bare_sheet(hierarchy: progsim.Hierarchy) -> progsim.Simulation:
    return progsim.Simulation(hierarchy, effects=EFFECTS, gravity=(0, 0, -9.81))


@pytest.fixture
def plate_file(tmp_path):
    path = tmp_path / "plate.obj"
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in PLATE] + [
        "f 1 2 3",
        "f 1 3 4",
    ]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_scene_built_in_code_steps_bit_for_bit_like_its_json(plate_file):
    with progsim.Simulation.from_scene(_scene(plate_file.name), plate_file.parent) as json_sim:
        sim = _bare_sheet(json_sim.hierarchy)
        assert sim.add_handle([0, 4]) == 0
        sim.set_handle_keyframes(0, [0.0, 0.1], [[0, 0, 0], [0, 0, 0.02]], interpolation="smooth")
        assert sim.add_handle(np.array([24], dtype=np.int64)) == 1
        sim.set_handle_motion(1, velocity=(0, 0, 0.1))
        assert sim.add_obstacle(PLATE, PLATE_FACES, friction=0.2) == 0
        sim.set_obstacle_keyframes(0, [0.0, 0.1], [[0, 0, 0], [0, 0, 0.01]])
        sim.set_ground(normal=(0, 0, 2), height=-0.1, friction=0.3)
        assert (
            (sim.num_handles, sim.num_obstacles)
            == (2, 1)
            == (
                json_sim.num_handles,
                json_sim.num_obstacles,
            )
        )
        with sim:
            for _ in range(15):
                json_sim.step_preview(1)
                sim.step_preview(1)
                assert np.array_equal(sim.positions(0), json_sim.positions(0))
            x = sim.positions(0)
        assert x[0, 2] == 0.02 and x[4, 2] == 0.02  # held at the last key
        assert x[24, 2] == pytest.approx(0.015, abs=1e-12)
        assert -0.02 < x[12, 2] < 0.0  # on the plate, which rose to -0.02 m


def _grid(n: int, size: float):
    """An n × n quad grid of side `size` in the x-y plane (vertex (i, j) at (n + 1) j + i)."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
    vertices = np.column_stack([i.ravel() * size / n, j.ravel() * size / n, np.zeros(i.size)])
    faces = []
    for jj in range(n):
        for ii in range(n):
            a, b = jj * (n + 1) + ii, jj * (n + 1) + ii + 1
            c, d = b + n + 1, a + n + 1
            faces += [(a, b, c), (a, c, d)]
    return vertices, np.array(faces)


def test_a_progressive_obstacle_added_in_code_holds_the_sheet_on_every_level():
    vertices, faces = _grid(12, 0.4)
    corners = [0, 12, 156, 168]
    hierarchy = progsim.Hierarchy(vertices, faces, coarse_vertex_counts=[40], pinned=corners)
    with progsim.Simulation(
        hierarchy,
        mode="quasistatic",
        effects=["membrane", "bending", "gravity", "contact"],
        gravity=(0, 0, -9.81),
        youngs_modulus=1e5,
        pinned=corners,
    ) as sim:
        with pytest.raises(progsim.InvalidArgumentError, match="vertex groups"):
            sim.add_handle([84])  # not a vertex group of the hierarchy
        plate, plate_faces = _grid(8, 0.2)
        sim.add_obstacle(plate + [0.1, 0.1, -0.01], plate_faces, progressive=True)
        sim.step_preview(3)
        while sim.current_level < sim.num_levels - 1:
            sim.refine()
        sim.settle(30)
        x = sim.positions()
        over = (x[:, 0] > 0.1) & (x[:, 0] < 0.3) & (x[:, 1] > 0.1) & (x[:, 1] < 0.3)
        assert over.sum() >= 25
        assert (x[over, 2] > -0.01).all()  # never through the plate
        assert x[84, 2] < -0.008  # the centre sags onto it


def test_bad_objects_are_refused_and_change_nothing(plate_file):
    with progsim.Simulation.from_scene(_scene(plate_file.name), plate_file.parent) as json_sim:
        with _bare_sheet(json_sim.hierarchy) as sim:
            spike = np.array([[0.15, 0.2, -0.05], [0.25, 0.2, -0.05], [0.2, 0.2, 0.05]])
            with pytest.raises(progsim.IntersectingError, match="obstacle face 0 cross"):
                sim.add_obstacle(spike, [[0, 1, 2]])
            with pytest.raises(progsim.InvalidMeshError, match=r"obstacles\[0\]"):
                sim.add_obstacle(PLATE, [[0, 1, 2], [0, 2, 4]])
            with pytest.raises(progsim.InvalidSceneError, match="friction"):
                sim.add_obstacle(PLATE, PLATE_FACES, friction=-1)
            with pytest.raises(progsim.InvalidSceneError, match="vertex 25 is out of range"):
                sim.add_handle([25])
            with pytest.raises(progsim.InvalidSceneError, match="selects no vertices"):
                sim.add_handle([])
            with pytest.raises(progsim.OutOfRangeError, match="obstacle 0 does not exist"):
                sim.set_obstacle_motion(0, velocity=(0, 0, 1))
            with pytest.raises(progsim.IntersectingError, match="ground"):
                sim.set_ground(normal=(0, 0, 1), height=0.1)
            with pytest.raises(progsim.InvalidArgumentError, match="normal"):
                sim.set_ground(normal=(0, 0, 0))
            assert (sim.num_handles, sim.num_obstacles) == (0, 0)
            sim.add_obstacle(PLATE, PLATE_FACES)
            with pytest.raises(progsim.InvalidArgumentError, match=r"keyframes\[1\]\.time"):
                sim.set_obstacle_keyframes(0, [0.1, 0.05], [[0, 0, 0], [0, 0, 0.01]])
            sim.step_preview(1)
            with pytest.raises(progsim.WrongCallOrderError, match="before the first step"):
                sim.add_handle([24])
            sim.set_ground(normal=(0, 0, 1), height=-0.5)  # between steps: allowed
            sim.step_preview(1)


def test_named_options_from_keywords_equal_the_scene_file():
    clamp = list(range(10))
    scene = {
        "simulation": {"mode": "quasistatic"},
        "gravity": [0, 0, -9.81],
        "effects": ["membrane", "bending", "gravity"],
        "bodies": [
            {
                "mesh": {"generator": "grid", "width": 0.4, "height": 0.4, "nx": 4, "ny": 4},
                "material": {"bending_model": "midedge"},
            }
        ],
        "handles": [{"body": 0, "vertices": clamp}],
        "progressive": {"levels": [12], "proxy_hessian": "galerkin", "prolongation": "direct"},
    }
    assert progsim.CHOICES["progressive.proxy_hessian"] == ("auto", "level", "galerkin")
    with progsim.Simulation.from_scene(scene) as json_sim:
        with progsim.Simulation(
            json_sim.hierarchy,
            mode="quasistatic",
            gravity=(0, 0, -9.81),
            pinned=clamp,
            bending_model="midedge",
            proxy_hessian="galerkin",
            prolongation="direct",
        ) as sim:
            assert sim.choice("progressive.prolongation") == "direct"
            assert sim.choice("progressive.preview_membrane") == "neo_hookean"  # the default
            for each in (json_sim, sim):
                each.step_preview(1)
                each.refine()
                each.step_preview(1)
            assert np.array_equal(sim.positions(1), json_sim.positions(1))
            assert sim.positions(1)[24, 2] < -1e-3
            with pytest.raises(progsim.InvalidArgumentError, match=r"known: auto, level, galerkin"):
                sim.set_choice("progressive.proxy_hessian", "exact")
            with pytest.raises(progsim.InvalidArgumentError, match="unknown option"):
                sim.choice("smoothing")


def test_wind_strain_limit_friction_and_contact_settings_from_code_equal_json():
    """The keywords reach every table row a scene's material, contact and wind sections set:
    a pinned sheet in keyframed gusts, strain-limited, over a frictional ground, built in code,
    steps bit for bit like its JSON."""
    effects = EFFECTS + ["strain_limit", "wind"]
    scene = {
        "simulation": {"time_step": 0.01},
        "gravity": [0, 0, -9.81],
        "effects": effects,
        "bodies": [
            {
                "mesh": {"generator": "grid", "width": 0.4, "height": 0.4, "nx": 4, "ny": 4},
                "material": {"friction": 0.4, "strain_limit": 1.05},
            }
        ],
        "contact": {"dhat": 2e-3, "stiffness": 50.0, "friction_velocity": 2e-3},
        "wind": {
            "keyframes": [
                {"time": 0, "velocity": [3, 0, 1]},
                {"time": 0.1, "velocity": [0, 2, 1]},
            ],
            "density": 1.1,
            "drag": 1.5,
            "lift": 0.3,
        },
        "handles": [{"body": 0, "vertices": [0, 4]}],
        "ground": {"normal": [0, 0, 1], "height": -0.05, "friction": 0.3},
    }
    with progsim.Simulation.from_scene(scene) as json_sim:
        code = progsim.Simulation(
            json_sim.hierarchy,
            effects=effects,
            gravity=(0, 0, -9.81),
            friction=0.4,
            strain_limit=1.05,
            dhat=2e-3,
            contact_stiffness=50.0,
            friction_velocity=2e-3,
            wind_keyframes=[[0, 3, 0, 1], [0.1, 0, 2, 1]],
            wind_density=1.1,
            wind_drag=1.5,
            wind_lift=0.3,
        )
        with code:
            code.add_handle([0, 4])
            code.set_ground(normal=(0, 0, 1), height=-0.05, friction=0.3)
            for name in (
                "material.friction",
                "material.strain_limit",
                "contact.dhat",
                "contact.stiffness",
                "contact.friction_velocity",
            ):
                assert code.get_param(name) == json_sim.get_param(name), name
            for _ in range(15):
                json_sim.step_preview(1)
                code.step_preview(1)
                assert np.array_equal(code.positions(0), json_sim.positions(0))
            assert not np.array_equal(code.positions(0), json_sim.hierarchy.rest_positions(0))
