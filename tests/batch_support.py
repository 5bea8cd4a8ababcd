"""Shared by the batch tests: input files and comparisons of batch outputs."""

from __future__ import annotations

import json
from pathlib import Path

from app.batch.scenes import MARKER, SCENES, figures_of

INSTRUCTIONS = [("Put a chilled bread on the counter", "kitchen"),
                ("Put a washed apple in the fridge", "kitchen"),
                ("Turn on the lamp and look at the book", "living room"),
                ("Put the pillow on the sofa", "living room"),
                ("Put a heated mug on the table", "dining room"),
                ("Put the alarm clock on the desk", "bedroom"),
                ("Put the soap bar in the bathtub", "bathroom"),
                ("Put the pen on the desk", "office")]

TIMING_KEYS = ("total_s", "per_object_s")  # layout.json's wall times: the only figures that differ run to run


def write_lines(path: Path, n: int, extra: list[str] = ()) -> Path:
    lines = [json.dumps({"instruction": ins, "room_type": room, "seed": i, "solver": "dfs"})
             for i, (ins, room) in ((i, INSTRUCTIONS[i % len(INSTRUCTIONS)]) for i in range(n))]
    path.write_text("\n".join([*lines, *extra]) + "\n")
    return path


def _without_timing(value):
    if isinstance(value, dict):
        return {k: _without_timing(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [_without_timing(v) for v in value]
    return value


def scene_files(out: Path) -> dict[str, object]:
    """Every exported file of a batch, keyed by scene/file; layout.json without its wall times."""
    files = {}
    for folder in sorted((out / SCENES).iterdir()):
        for f in sorted(folder.iterdir()):
            if f.name == MARKER:
                continue
            key = f"{folder.name}/{f.name}"
            files[key] = _without_timing(json.loads(f.read_text())) if f.name == "layout.json" else f.read_bytes()
    return files


def results(out: Path) -> list[dict]:
    return [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]


def figures(out: Path) -> list[dict]:
    """The results rows without what depends on the clock or the worker (timings, pid)."""
    return [figures_of(r) for r in results(out)]
