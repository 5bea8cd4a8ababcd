"""The task scene graph drawn as a picture (the paper's Figure 1): objects as role-coloured nodes,
relations as labelled arrows, the room type as the caption."""

from __future__ import annotations

import math

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from models.exports.glb import ROLE_COLOURS
from models.values import TaskGraph


def _colour(roles: list[str]) -> tuple[float, float, float]:
    role = "anchor" if "anchor" in roles else roles[0]
    return tuple(c / 255 for c in ROLE_COLOURS[role][:3])


def render(graph: TaskGraph, width_px: int = 480, height_px: int = 300) -> np.ndarray:
    """RGB image (H, W, 3) of the graph."""
    fig = Figure(figsize=(width_px / 100, height_px / 100), dpi=100)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(-1.6, 1.6)
    ax.set_ylim(-1.25, 1.25)
    ax.axis("off")
    target = graph.target
    others = [o for o in graph.objects if o.type != target]
    pos = {}
    if target is not None:
        pos[target] = (-0.9, 0.0)
    if len(others) == 1 and target is None:  # a lone object (no relation): in the middle
        pos[others[0].type] = (0.0, 0.0)
        others = []
    for i, o in enumerate(others):
        angle = math.pi / 2 - math.pi * (i + 0.5) / max(len(others), 1) if target else 2 * math.pi * i / len(others)
        pos[o.type] = (0.2 + 1.0 * math.cos(angle), 0.95 * math.sin(angle))
    for a, rel, b in graph.relations:
        (x0, y0), (x1, y1) = pos[a], pos[b]
        ax.annotate("", xy=(x1, y1), xytext=(x0, y0),
                    arrowprops={"arrowstyle": "->", "color": "#555", "lw": 1.4, "shrinkA": 28, "shrinkB": 28})
        ax.text((x0 + x1) / 2, (y0 + y1) / 2 + 0.06, rel.replace("_", " "), fontsize=8, ha="center", color="#333")
    for o in graph.objects:
        x, y = pos[o.type]
        ax.text(x, y, f"{o.type}\n{' + '.join(o.roles)}", ha="center", va="center", fontsize=9, color="white",
                bbox={"boxstyle": "round,pad=0.5", "fc": _colour(o.roles), "ec": "none"})
    ax.text(0, -1.15, f"room: {graph.room_type}   task: {graph.task_type}", ha="center", fontsize=8, color="#333")
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()
