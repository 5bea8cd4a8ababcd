"""`h3ds edit` and `h3ds scenes`: a scene's folder (what `h3ds generate` writes) edited as the studio edits it, stored
in the studio's database as a scene or its next version, and a stored version written back to a folder."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

from pydantic import ValidationError

from app.cli_input import BadInput, load_value

EDIT_LOG = "edits.jsonl"  # `h3ds edit`'s log in the folder, one row per edit as the studio stores them


def cmd_edit(args) -> int:
    """The studio's edits on a folder of `h3ds generate`: the files written again (to --out, or in place) and the
    edit appended to edits.jsonl; the checks that fail after it are printed, as the studio shows them."""
    from app.editing import EditError, apply_edits
    from app.pipeline import Pipeline, write_apartment, write_generation
    folder = Path(args.dir)
    value = _generated(folder)
    try:
        done = apply_edits(Pipeline(), value, _edit_steps(args), args.room, args.seed, args.solver)
    except EditError as e:
        option = {"room": "--room", "scene": str(folder / "scene.json")}.get(e.loc[0], _action(args))
        option = "--to-room" if e.loc[-1] == "to_room" and not args.edits else option
        where = f" [{e.loc[1]}]" if args.edits and e.loc[0] == "edits" else ""  # the list's index
        raise BadInput(f"{option}{where}: {e}") from e
    out = Path(args.out) if args.out else folder
    paths = write_generation(done.room, out) if done.value is done.room.scene else write_apartment(done.value, out)
    log, earlier = out / EDIT_LOG, folder / EDIT_LOG
    if out != folder and earlier.exists():
        log.write_text(earlier.read_text())
    with log.open("a") as f:
        for row in done.log:
            f.write(json.dumps(dataclasses.asdict(row)) + "\n")
    for p in [*paths, log]:
        print(p)
    for finding in done.findings:
        print(f"check: {finding.text.replace('`', '')}", file=sys.stderr)
    return 0


def _generated(folder: Path):
    """The scene or apartment a folder of `h3ds generate` holds (scene.json or apartment.json)."""
    from models.values import Scene
    from models.values.apartment import Apartment
    for name, model in (("scene.json", Scene), ("apartment.json", Apartment)):
        if (folder / name).exists():
            return load_value(str(folder / name), model, name.removesuffix(".json"))
    raise BadInput(f"{folder}: holds no scene.json or apartment.json (h3ds generate writes one; a folder written "
                   "before it did must be generated again)")


def _action(args) -> str:
    return ("--move" if args.move else "--constraints" if args.constraints else "--edits" if args.edits else
            "--replace-around")


def _edit_steps(args) -> list:
    """The edits the options ask for: --edits' list, or the one edit of the other options."""
    from app.editing import EditList
    if not args.edits:
        return [_edit_step(args)]
    if args.to_room is not None:
        raise BadInput("--to-room goes with --move (in --edits, a move's \"to_room\")")
    try:
        raw = sys.stdin.read() if args.edits == "-" else Path(args.edits).read_text()
        return EditList.validate_json(raw)
    except (OSError, UnicodeDecodeError) as e:
        raise BadInput(f"--edits: cannot read {args.edits} ({e})") from e
    except ValidationError as e:
        first = e.errors()[0]
        index, *field = first["loc"] or [None]  # the list's index, then the field (after the kind's tag)
        where = "" if index is None else f" [{index}]" + "".join(f".{p}" for p in field)
        raise BadInput(f"--edits{where}: {first['msg']}") from e


def _edit_step(args):
    """The one edit the options ask for."""
    from app.editing import Constraints, Move, ReplaceAround
    if args.move:
        if len(args.move) not in (3, 4):
            raise BadInput(f"--move takes ID X Z [ROTATION], not {len(args.move)} value(s)")
        try:
            numbers = [float(v) for v in args.move[1:]]
        except ValueError as e:
            raise BadInput(f"--move: X, Z and ROTATION are numbers ({e})") from e
        return Move(object=args.move[0], x=numbers[0], z=numbers[1], rotation=numbers[2] if len(numbers) > 2 else None,
                    to_room=args.to_room)
    if args.to_room is not None:
        raise BadInput("--to-room goes with --move")
    if args.constraints:
        try:
            text = sys.stdin.read() if args.constraints == "-" else Path(args.constraints).read_text()
        except (OSError, UnicodeDecodeError) as e:
            raise BadInput(f"--constraints: cannot read {args.constraints} ({e})") from e
        return Constraints(text=text.strip("\n"))
    ids = [i.strip() for i in args.replace_around.split(",") if i.strip()]
    if not ids:
        raise BadInput("--replace-around: name at least one object id")
    return ReplaceAround(objects=ids)


def cmd_scenes_list(args) -> int:
    from studio_db import Store
    for row in Store().list_scenes():
        print(f"{row['id']:5d}  {row['room_type']:12s} {row['versions']:3d} version(s)  {row['name']}")
    return 0


def cmd_scenes_export(args) -> int:
    """A stored version written as `h3ds generate` writes a scene (and `h3ds edit` reads it)."""
    from app.pipeline import generation_of, write_apartment, write_generation
    from models.values import Scene
    from studio_db import NotFound, Store
    try:
        stored = Store().scene(args.id, args.version)
    except NotFound as e:
        raise BadInput(str(e)) from e
    if isinstance(stored, Scene):
        try:
            paths = write_generation(generation_of(stored), Path(args.out))
        except ValueError as e:
            raise BadInput(f"scene {args.id}: {e}") from e
    else:
        paths = write_apartment(stored, Path(args.out))
    for p in paths:
        print(p)
    return 0


def cmd_scenes_store(args) -> int:
    """A folder's scene as a new stored scene, or as the next version of `--scene`, with its edit log; the log is
    then kept beside it as edits-<scene>-v<version>.jsonl, so that it is not stored twice."""
    from app.editing import generated_seed
    from models.values.apartment import Apartment
    from studio_db import NotFound, Store
    from models.values.edit import Edit
    from studio_db.store import WrongKind
    folder = Path(args.dir)
    value = _generated(folder)
    rows = _edit_rows(folder / EDIT_LOG)
    first = value.scenes[0] if isinstance(value, Apartment) and value.scenes else value
    seed = generated_seed(first)
    solver = next((p.method for p in first.provenance if p.stage == "layout"), "stored")
    edits = [Edit(r["kind"], r["target"], r.get("before"), r.get("after")) for r in rows]
    store = Store()
    try:
        if args.scene is None:
            scene_id, number = store.create_scene(args.name, value, seed, solver, edits)
        else:
            scene_id, number = args.scene, store.add_version(args.scene, args.name, value, seed, solver, edits)
    except (NotFound, WrongKind) as e:
        raise BadInput(f"--scene: {e}") from e
    if rows:
        (folder / EDIT_LOG).rename(folder / f"edits-{scene_id}-v{number}.jsonl")
    print(f"stored as scene {scene_id}, version {number} ({len(rows)} edit(s)) in {store.location.split('@')[-1]}")
    return 0


def _edit_rows(path: Path) -> list[dict]:
    """The rows of an edit log, each checked; a bad line is a BadInput naming it."""
    if not path.exists():
        return []
    rows = []
    for n, line in enumerate(path.read_text().splitlines(), start=1):
        try:
            row = json.loads(line)
        except json.JSONDecodeError as e:
            raise BadInput(f"{path}: line {n}: not valid JSON ({e})") from e
        if not isinstance(row, dict) or not isinstance(row.get("kind"), str) or not isinstance(row.get("target"), str):
            raise BadInput(f"{path}: line {n}: an edit is an object with text kind and target")
        rows.append(row)
    return rows


def add_scene_commands(sub, solver_help: str, solver_list: str) -> None:
    """`edit` and `scenes` on the command line's subparsers."""
    p = sub.add_parser("edit", help="the studio's edits on a folder of h3ds generate: move an object, edit the "
                       "constraints, re-place around objects", epilog=solver_list,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dir", metavar="DIR", help="a folder written by h3ds generate (its scene.json or apartment.json)")
    what = p.add_mutually_exclusive_group(required=True)
    what.add_argument("--move", nargs="+", metavar="ID X Z [ROTATION]", help="put one object at x, z (metres, in "
                      "its room's frame, as layout.json) facing ROTATION degrees (default: as it was)")
    what.add_argument("--constraints", metavar="FILE", help="the room's constraint text edited (Holodeck's lines, "
                      "as in plan.json; - for stdin): placed again from the first object whose lines changed")
    what.add_argument("--replace-around", metavar="ID[,ID...]", help="keep these objects where they are and place "
                      "the others again around them")
    what.add_argument("--edits", metavar="FILE", help="several edits in order, a JSON list as POST /edit's \"edits\" "
                      "(each may name its own \"room\"); - for stdin")
    p.add_argument("--room", type=int, default=None, help="an apartment's room to edit: its number, as in "
                   "rooms/N-TYPE (default: the room of the object --move or --replace-around names)")
    p.add_argument("--to-room", type=int, default=None, metavar="N", help="with --move in an apartment: carry the "
                   "object into room N (X, Z in that room's frame); it takes that room's id prefix (r3-...)")
    p.add_argument("--seed", type=int, default=None, help="default: the seed the scene was generated with")
    p.add_argument("--solver", default=None, help=solver_help)
    p.add_argument("--out", metavar="DIR", default=None, help="write the edited scene here (default: DIR itself)")
    p.set_defaults(run=cmd_edit)


    p = sub.add_parser("scenes", help="the studio's stored scenes: list, export a version to a folder, store a folder")
    scenes = p.add_subparsers(dest="scenes_command", required=True)
    s = scenes.add_parser("list", help="id, room type, versions and name of every stored scene, newest first")
    s.set_defaults(run=cmd_scenes_list)
    s = scenes.add_parser("export", help="a stored version as the folder h3ds generate writes (h3ds edit reads it)")
    s.add_argument("id", type=int, metavar="SCENE")
    s.add_argument("--version", type=int, default=None, help="default: the latest")
    s.add_argument("--out", required=True, metavar="DIR")
    s.set_defaults(run=cmd_scenes_export)
    s = scenes.add_parser("store", help="a folder's scene (and its edits.jsonl) as a new scene, or the next version "
                          "of --scene")
    s.add_argument("dir", metavar="DIR", help="a folder of h3ds generate, h3ds edit or h3ds scenes export")
    s.add_argument("--name", required=True, help="the version's name, as the studio's Save name")
    s.add_argument("--scene", type=int, default=None, metavar="ID", help="store as this scene's next version")
    s.set_defaults(run=cmd_scenes_store)
