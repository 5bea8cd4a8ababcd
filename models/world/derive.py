"""Derive the compact world-model data in ``models/data`` from the raw AI2-THOR / ProcTHOR / ALFRED files.

This is a maintainer's tool, run once when the upstream data changes; nothing at run time or in the
tests calls it. Usage::

    python -m models.world.derive --shared PATH/TO/shared/data

Every output is deterministic (sorted keys, fixed rounding) so that a re-run gives identical bytes.
"""

from __future__ import annotations

import argparse
import csv
import gzip
import json
import statistics
from collections import Counter, defaultdict
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "data"

# iTHOR groups of ai2thor-object-metadata.json and the room type each one is.
ITHOR_GROUPS = {"kitchens": "kitchen", "living_rooms": "living room", "bedrooms": "bedroom", "bathrooms": "bathroom"}
FLAGS = ["pickupable", "receptacle", "isHeatSource", "isColdSource", "toggleable", "openable", "moveable",
         "breakable", "cookable", "sliceable", "dirtyable", "canFillWithLiquid", "canBeUsedUp"]
PLACEMENT = {"onFloor": "on_floor", "onWall": "on_wall", "onEdge": "on_edge", "inCorner": "in_corner",
             "inMiddle": "in_middle", "multiplePerRoom": "multiple_per_room", "isStructure": "is_structure"}
ALFRED_KEYS = ["split", "task_type", "task_desc", "object_target", "parent_target", "toggle_target",
               "object_sliced", "floor_plan"]


def r3(v: float) -> float:
    return round(float(v), 3)


def write_json(name: str, data) -> None:
    (OUT / name).write_text(json.dumps(data, sort_keys=True, separators=(",", ":")) + "\n")


def write_gz(name: str, lines: list[str]) -> None:
    with gzip.GzipFile(OUT / name, "wb", mtime=0) as f:
        f.write(("\n".join(lines) + "\n").encode())


def ithor_scenes(meta: dict) -> list[dict]:
    """One record per hand-designed iTHOR room: its type and its objects' type, pose and size."""
    offsets = {"kitchens": 1, "living_rooms": 201, "bedrooms": 301, "bathrooms": 401}
    scenes = []
    for group, room_type in ITHOR_GROUPS.items():
        for i, objects in enumerate(meta[group]):
            by_id = {o["objectId"]: o["objectType"] for o in objects}
            scenes.append({
                "scene": f"FloorPlan{offsets[group] + i}",
                "room_type": room_type,
                "objects": [{
                    "type": o["objectType"],
                    "x": r3(o["axisAlignedBoundingBox"]["center"]["x"]),
                    "y": r3(o["axisAlignedBoundingBox"]["center"]["y"]),
                    "z": r3(o["axisAlignedBoundingBox"]["center"]["z"]),
                    "rotation": r3(o["rotation"]["y"]) % 360,
                    "size": [r3(o["axisAlignedBoundingBox"]["size"][k]) for k in "xyz"],
                    "parents": sorted({by_id.get(p, p.split("|")[0]) for p in (o["parentReceptacles"] or [])}),
                } for o in objects],
            })
    return scenes


def room_frequencies(scenes: list[dict]) -> dict[str, dict[str, dict[str, float]]]:
    """type -> room type -> {presence: share of rooms that have it, mean_count: count where present}."""
    counts: dict[str, dict[str, list[int]]] = defaultdict(lambda: defaultdict(list))
    per_room = Counter(s["room_type"] for s in scenes)
    for s in scenes:
        for t, n in Counter(o["type"] for o in s["objects"]).items():
            counts[t][s["room_type"]].append(n)
    return {t: {rt: {"presence": r3(len(ns) / per_room[rt]), "mean_count": r3(statistics.mean(ns))}
                for rt, ns in sorted(rooms.items())} for t, rooms in counts.items()}


def catalogue(shared: Path, scenes: list[dict]) -> dict:
    proc = shared / "procthor"
    assets = json.loads((proc / "asset-database.json").read_text())
    annotations = json.loads((proc / "placement-annotations.json").read_text())
    receptacles = json.loads((proc / "receptacles.json").read_text())
    freq = room_frequencies(scenes)
    rows = {r["objectType"]: r for r in csv.DictReader(open(shared / "ai2thor" / "object_types.csv"))}
    types = {}
    for t in sorted(set(rows) | set(assets)):
        row = rows.get(t)
        entry: dict = {"assets": [[a["assetId"], *(r3(a["boundingBox"][k]) for k in "xyz"), a.get("split")]
                                  for a in sorted(assets.get(t, []), key=lambda a: a["assetId"])]}
        if row:
            entry["flags"] = {f: float(row[f]) >= 0.5 for f in FLAGS}
            entry["mass"] = r3(row["mass_median"])
            entry["size"] = [r3(row[f"aabb_{k}_median"]) for k in "xyz"]
            entry["materials"] = [m for m in row["salientMaterials"].split(";") if m]
        else:  # structural types (doors, windows) that only the asset database lists
            entry["flags"] = {f: False for f in FLAGS}
            first = assets[t][0]
            entry["size"] = [r3(first["boundingBox"][k]) for k in "xyz"]
            entry["mass"] = 0.0
            entry["materials"] = []
        entry["placement"] = {new: annotations[old].get(t) for old, new in PLACEMENT.items()}
        entry["rooms"] = freq.get(t, {})
        entry["contents"] = {c: r3(v["p"]) for c, v in sorted(receptacles.get(t, {}).items())}
        swings = [a["states"]["open"]["boundingBox"]["z"] - a["boundingBox"]["z"]
                  for a in assets.get(t, []) if "open" in (a.get("states") or {})]
        entry["open_swing"] = r3(statistics.median(swings)) if swings else 0.0
        types[t] = entry
    return types


def structure(shared: Path) -> dict:
    """Door and window assets with their hole sizes, and floor / wall material names."""
    proc = shared / "procthor"
    holes = json.loads((proc / "wall-holes.json").read_text())
    materials = json.loads((proc / "material-database.json").read_text())

    def hole(k: str) -> dict:
        h = holes[k]
        return {"width": r3(h["max"]["x"] - h["min"]["x"]), "height": r3(h["max"]["y"] - h["min"]["y"]),
                "sill": r3(h["min"]["y"]), "offset_x": r3(h["offset"]["x"])}

    floor = sorted({m for group in ("Wood",) for m in materials[group]}
                   | {m for ms in materials.values() for m in ms if "floor" in m.lower()})
    return {"doors": {k: hole(k) for k in sorted(holes) if k.startswith("Doorway")},
            "windows": {k: hole(k) for k in sorted(holes) if k.startswith("Window")},
            "floor_materials": floor, "wall_materials": sorted(materials["Wall"])}


def asset_groups(shared: Path) -> dict:
    """ProcTHOR's furniture arrangements, reduced to member types, relative poses and room weights."""
    groups = {}
    for path in sorted((shared / "procthor" / "asset_groups").glob("*.json")):
        g = json.loads(path.read_text())
        members = []
        for m in g["assetMetadata"].values():
            members.append({"type": m["name"], "x": r3(m["position"]["x"]), "z": r3(m["position"]["z"]),
                            "rotation": r3(m["rotation"]), "assets": sorted(next(iter(m["assetIds"].values())))})
        props = g["groupProperties"]
        groups[path.stem] = {"members": members, "location": props["location"],
                             "room_weights": props["roomWeights"],
                             "allow_duplicates": props["properties"].get("allowDuplicates", False)}
    return groups


def alfred(shared: Path) -> list[str]:
    lines = []
    with open(shared / "alfred" / "annotations_4types.jsonl") as f:
        for line in f:
            row = json.loads(line)
            lines.append(json.dumps({k: row[k] for k in ALFRED_KEYS}, sort_keys=True, separators=(",", ":")))
    return lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", type=Path, required=True, help="the shared/data folder with the raw files")
    shared = ap.parse_args().shared
    meta = json.load(gzip.open(shared / "procthor" / "ai2thor-object-metadata.json.gz"))
    scenes = ithor_scenes(meta)
    OUT.mkdir(exist_ok=True)
    write_json("catalogue.json", catalogue(shared, scenes))
    write_json("structure.json", structure(shared))
    write_json("asset_groups.json", asset_groups(shared))
    constants = json.loads((shared / "alfred" / "constants.json").read_text())
    write_json("alfred_constants.json", {k: constants[k] for k in
                                         ("GOALS_VALID", "VAL_RECEPTACLE_OBJECTS", "VAL_ACTION_OBJECTS")})
    write_gz("alfred_annotations.jsonl.gz", alfred(shared))
    write_gz("ithor_scenes.jsonl.gz", [json.dumps(s, sort_keys=True, separators=(",", ":")) for s in scenes])
    print(f"wrote {sorted(p.name for p in OUT.iterdir())}")


if __name__ == "__main__":
    main()
