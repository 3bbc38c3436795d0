"""A contact sheet of a sweep's runs: each run's last preview frame in one PNG (matplotlib)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Sequence, Union

import numpy as np

__all__ = ["draw_contact_sheet"]


def _title(result: Any) -> str:
    """Run index and parameter values, short enough for a small panel."""
    parts = [f"#{result.index}"]
    for name, value in result.values.items():
        short = name.rsplit(".", 1)[-1]
        text = f"{value:.3g}" if isinstance(value, float) else json.dumps(value)
        parts.append(f"{short}={text[:24]}")
    return "\n".join([" ".join(parts[:2])] + parts[2:])


def _draw_run(axes: Any, result: Any, limits: np.ndarray) -> None:
    """One panel: the run's surface, or its status when it failed."""
    axes.set_title(_title(result), fontsize=7)
    if result.positions is None:
        axes.text2D(0.5, 0.5, result.status, transform=axes.transAxes, ha="center", color="red")
    else:
        x = result.positions
        axes.plot_trisurf(
            x[:, 0],
            x[:, 1],
            x[:, 2],
            triangles=result.faces,
            color="tab:blue",
            linewidth=0.1,
            edgecolor="k",
            alpha=0.9,
        )
    for setter, (low, high) in zip((axes.set_xlim, axes.set_ylim, axes.set_zlim), limits):
        setter(low, high)
    axes.set_box_aspect(limits[:, 1] - limits[:, 0] + 1e-12)
    axes.set_axis_off()


def _limits(results: Sequence[Any]) -> np.ndarray:
    """One (3, 2) box holding every run's last frame, so that panels compare."""
    frames = [r.positions for r in results if r.positions is not None]
    if not frames:
        return np.array([[-1.0, 1.0]] * 3)
    points = np.vstack(frames)
    low, high = points.min(axis=0), points.max(axis=0)
    pad = 0.02 * max(float(np.max(high - low)), 1e-9)  # a flat frame still gets a box
    return np.column_stack([low - pad, high + pad])


def draw_contact_sheet(results: Sequence[Any], path: Union[str, Path], columns: int = 4) -> None:
    """Writes a PNG with one 3D panel per run, all on the same axes' box."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns = max(1, min(columns, len(results)))
    rows = max(1, math.ceil(len(results) / columns))
    figure = plt.figure(figsize=(3.0 * columns, 3.0 * rows), dpi=100)
    limits = _limits(results)
    for slot, result in enumerate(results):
        _draw_run(figure.add_subplot(rows, columns, slot + 1, projection="3d"), result, limits)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
