"""`h3ds`: the command line of interfaces.md, a thin shell over app.pipeline.

Bad input never shows a traceback: it exits with status 2 and one line on stderr naming the problem.
"""

from __future__ import annotations

import argparse
import json
import sys
from contextlib import nullcontext
from pathlib import Path

from pydantic import ValidationError

from app.cli_input import BadInput, Parser, load_value, value_error
from app.cli_scenes import add_scene_commands
from models.errors import InputError
from models.language.combined import DEFAULT_POLICY, POLICIES, make_parser
from models.placement import DEFAULT_SOLVER, SOLVERS
from models.placement.base import summaries
from models.planning.apartment_planner import is_apartment, parse_rooms
from models.world import ROOM_TYPES

EXAMPLES = """examples:
  h3ds parse "Put a chilled bread on the counter" --room-type kitchen
  h3ds generate "Put a chilled bread on the counter" --room-type kitchen --out out/bread
  h3ds generate "Put a chilled bread on the counter" --room-type apartment --rooms "kitchen, bedroom" --out out/flat
  h3ds place out/bread/plan.json --solver dfs --seed 3 --out layout.json
  h3ds edit out/bread --move fridge-0 0.5 3.0 90
  h3ds edit out/flat --room 2 --replace-around r2-sofa-0
  h3ds scenes store out/bread --name "bread, fridge moved"
"""

SOLVER_HELP = f"placer: {DEFAULT_SOLVER} (default); one of {', '.join(sorted(SOLVERS))} (listed below)"
SOLVER_LIST = "solvers:\n" + "\n".join(f"  {name:24s}{line}" for name, line in summaries().items())


def load_plan(path: str):
    from models.values import ConstraintPlan
    return load_value(path, ConstraintPlan, "plan")


def load_kept(path: str, plan) -> dict[str, tuple[float, float, float]]:
    """The poses of a layout file's placements, to keep when placing `plan` (`h3ds place --keep`)."""
    from app.pipeline import outside, pose_of, strangers
    from models.values import Layout
    keep = {p.id: pose_of(p) for p in load_value(path, Layout, "layout").placements}
    if unknown := strangers(plan, keep):
        raise BadInput(f"{path}: not objects of plan {plan.id}: {', '.join(unknown)}")
    if far := outside(plan, keep):
        raise BadInput(f"{path}: {far}")
    return keep


def _parser_of(args):
    """The instruction parser `--parser` names, `combined` if only `--policy` is given (None: the pipeline's
    default)."""
    if args.policy and not args.parser:
        args.parser = "combined"
    if not args.parser:
        return None
    if args.policy and args.parser != "combined":
        raise BadInput(f"--policy is for --parser combined, not {args.parser}")
    options = {"base_url": args.openai_url, "model": args.openai_model} if args.parser == "openai" else \
        {"policy": args.policy}
    return make_parser(args.parser, **options)


def cmd_parse(args) -> int:
    from app.pipeline import Pipeline, dump
    pipeline = Pipeline(parser=_parser_of(args))
    if args.batch:
        out = open(args.out, "w") if args.out else sys.stdout
        try:
            for n, line in enumerate(Path(args.batch).read_text().splitlines(), start=1):
                if not line.strip():
                    continue
                try:
                    item = json.loads(line)
                    graph = pipeline.parse(item["instruction"], item.get("room_type"))
                    row = {"id": item.get("id"), **json.loads(dump(graph))}
                except (json.JSONDecodeError, KeyError, TypeError, InputError) as e:
                    row = {"id": item.get("id") if isinstance(item, dict) else None, "error": f"line {n}: {e}"}
                out.write(json.dumps(row) + "\n")
        finally:
            if args.out:
                out.close()
        return 0
    if args.instruction is None:
        raise BadInput("give an INSTRUCTION or --batch IN.jsonl")
    print(dump(pipeline.parse(args.instruction, args.room_type)))
    return 0


def cmd_place(args) -> int:
    from app.pipeline import Pipeline, dump
    pipeline = Pipeline()
    plans = [load_plan(p) for p in args.plans]
    if len(plans) > 1 and not args.out_dir:
        raise BadInput("several plans need --out-dir DIR")
    if args.steps and (len(plans) > 1 or (args.steps == "-" and not args.out)):
        raise BadInput("--steps takes one plan; --steps - (steps on stdout) needs --out LAYOUT.json")
    if args.keep and len(plans) > 1:
        raise BadInput("--keep takes one plan")
    for plan in plans:
        keep = load_kept(args.keep, plan) if args.keep else None
        layout = _place_stepwise(pipeline, plan, args, keep) if args.steps else \
            pipeline.place(plan, seed=args.seed, solver=args.solver, keep=keep)
        if args.out_dir:
            Path(args.out_dir).mkdir(parents=True, exist_ok=True)
            (Path(args.out_dir) / f"{plan.id}.json").write_text(dump(layout) + "\n")
        elif args.out:
            Path(args.out).write_text(dump(layout) + "\n")
        else:
            print(dump(layout))
    return 0


def _place_stepwise(pipeline, plan, args, keep):
    """Place `plan` (`keep`: poses kept), writing each step as a JSON line to `args.steps` (a path, or - for
    stdout) as it is made."""
    from models.placement.stepping import step_record
    stepping = pipeline.stepping(plan, seed=args.seed, solver=args.solver, keep=keep)
    with (nullcontext(sys.stdout) if args.steps == "-" else open(args.steps, "w")) as out:
        for k, step in enumerate(stepping, 1):
            print(json.dumps(step_record(step, k)), file=out, flush=True)
    return stepping.layout


def cmd_generate(args) -> int:
    from app.pipeline import Pipeline, write_generation
    if is_apartment(args.room_type):
        return _generate_apartment(args)
    if args.rooms is not None:
        raise BadInput("--rooms needs --room-type apartment")
    gen = Pipeline(parser=_parser_of(args)).generate(args.instruction, args.room_type, seed=args.seed,
                                                     solver=args.solver)
    paths = write_generation(gen, Path(args.out))
    for p in paths:
        print(p)
    if gen.scene.unplaced:
        print(f"note: {len(gen.scene.unplaced)} object(s) could not be placed; see layout.json", file=sys.stderr)
    return 0


def _generate_apartment(args) -> int:
    from app.pipeline import Pipeline, write_apartment
    rooms = parse_rooms(args.rooms)
    apartment = Pipeline(parser=_parser_of(args)).generate_apartment(args.instruction, rooms, seed=args.seed,
                                                                     solver=args.solver)
    for p in write_apartment(apartment, Path(args.out)):
        print(p)
    for u in apartment.unplaced:
        print(f"note: {u.id} could not be placed: {u.reason}", file=sys.stderr)
    return 0


def cmd_demo(args) -> int:
    from app.pipeline import Pipeline, write_generation
    out = Path(args.out)
    gen = Pipeline().generate("Put a chilled bread on the counter", "kitchen", seed=0)
    write_generation(gen, out)
    print(f"Demo scene for 'Put a chilled bread on the counter' written to {out.resolve()}/")
    print(f"  open {out / 'scene.glb'} in Blender or any glTF viewer; "
          f"load {out / 'house.json'} with AI2-THOR's Controller(scene=house)")
    return 0


def cmd_data(args) -> int:
    from app.batch.executors import executor_from_args
    from models.datasets.constraint_sets import ALL_SETS, write_dataset
    with executor_from_args(args, serial_default=True) as executor:  # one set per task
        done = {d.index: d for d in executor.run(write_dataset, ALL_SETS)}
    for i in range(len(ALL_SETS)):
        if done[i].error:
            print(f"h3ds: error: {ALL_SETS[i]}: {done[i].error}", file=sys.stderr)
            return 1
        path, digest = done[i].value
        print(f"{path}  sha256 {digest}")
    return 0


def cmd_batch_generate(args) -> int:
    from app.batch.executors import executor_from_args
    from app.batch.scenes import BatchError, run_batch
    try:
        with executor_from_args(args) as executor:
            plural = "" if executor.workers == 1 else "s"
            print(f"batch: {args.input} -> {args.out} on {executor.name} ({executor.workers} worker{plural})",
                  file=sys.stderr, flush=True)
            studio = _studio_database() if args.studio else None
            summary = run_batch(Path(args.input), Path(args.out), executor, args.parser, not args.no_progress, studio)
    except BatchError as e:
        raise BadInput(str(e)) from e
    print(f"{summary.done} generated, {summary.skipped} already complete, {summary.failed} failed of "
          f"{summary.total} lines in {summary.seconds:.1f} s; results: {Path(args.out) / 'results.jsonl'}")
    for line in summary.errors[:10]:
        print(f"  failed: {line}", file=sys.stderr)
    return 1 if summary.failed else 0


def _studio_database() -> str:
    from studio_db.store import default_database_url
    return default_database_url()


def cmd_studio(args) -> int:
    import time

    from app.pipeline import Pipeline
    from frontend.server import Studio, serve_api
    from studio_db import Store

    store, pipeline = Store(), Pipeline()
    studio = Studio(args.host, args.port, store, pipeline)
    _, api_port = serve_api(store, pipeline, args.host, args.api_port or studio.port + 1)
    shown = "localhost" if args.host in ("0.0.0.0", "127.0.0.1") else args.host
    print(f"H3DS Studio: http://{shown}:{studio.port}   (open it in a browser)")
    print(f"HTTP API:    http://{shown}:{api_port}/docs")
    print(f"Database:    {store.location}", flush=True)
    if args.simulated_headset:
        _start_simulated_headset(store, args.host, api_port)
    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        studio.stop()
    return 0


def _start_simulated_headset(store, host: str, api_port: int) -> None:
    """The headset simulator (a stand-in for the Quest app) as its own process, paired with the studio's
    current token over the wire protocol, as a real headset would be."""
    import subprocess
    import sys

    from app.bridge import HEADSET_PATH, bridge_for
    sim = Path(__file__).resolve().parents[1] / "unity-bridge" / "simulator" / "headset_sim.py"
    url = f"ws://{'127.0.0.1' if host == '0.0.0.0' else host}:{api_port}{HEADSET_PATH}"
    subprocess.Popen([sys.executable, str(sim), url, "--token", bridge_for(store).token])
    print("Headset:     the headset SIMULATOR (stand-in) is pairing; press 'Send to headset' in the Headset tab",
          flush=True)


def cmd_feedback_export(args) -> int:
    from app.bridge.export import jsonl
    from studio_db import Store
    from studio_db.feedback import FeedbackStore

    feedback = FeedbackStore(Store())
    try:
        lines = jsonl(feedback, args.since, args.until, args.scene, args.session)
        out = open(args.out, "w", encoding="utf-8") if args.out else sys.stdout
        count = 0
        for line in lines:
            out.write(line)
            count += 1
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.out:
        out.close()
        print(f"{count} feedback records -> {args.out}", file=sys.stderr)
    return 0


def cmd_train_language(args) -> int:
    from models.language.llm.data import augmented_examples, training_examples
    from models.language.llm.train import TrainConfig, train
    cfg = TrainConfig(out=args.out, base=args.base, seed=args.seed, epochs=args.epochs, max_steps=args.max_steps,
                      batch_size=args.batch_size, lr=args.lr, warmup=args.warmup, lora_r=args.lora_r,
                      lora_alpha=args.lora_alpha, lora_dropout=args.lora_dropout,
                      lora_layers=args.lora_layers or None, save_every=args.save_every, limit=args.limit,
                      threads=args.threads, init_adapter=args.init_adapter)
    if args.augment:
        from app.bench.language import kept_apart_texts, trained_rows
        rows = augmented_examples(trained_rows(), kept_apart_texts())
    else:
        rows = training_examples()
    adapter = train(cfg, rows)
    print(f"adapter: {adapter}  (loss curves: {Path(args.out) / 'loss.csv'}, {Path(args.out) / 'loss.png'})")
    print(f"use it: cp {adapter}/* models/weights/lora/   or   LoraParser(adapter='{adapter}')")
    return 0


def cmd_train_roles(args) -> int:
    from models.language.roles.train import RolesConfig, train
    cfg = RolesConfig(out=args.out, seed=args.seed, epochs=args.epochs, lr=args.lr, batch_size=args.batch_size,
                      limit=args.limit or None, eval_limit=args.eval_limit or None, lora=args.lora,
                      lora_lr=args.lora_lr)
    head = train(cfg)
    print(f"role model: {head}  (log: {Path(args.out) / 'train.csv'}, curves: {Path(args.out) / 'curves.png'})")
    print(f"measure it: python -m models.language.roles.evaluate {head}")
    return 0


def cmd_train_placement(args) -> int:
    from models.placement.plan2place.agent import TrainConfig, export_weights, plot_curves, train
    from models.placement.plan2place.network import NetConfig
    prior = {} if args.prior_temp is None else {"prior_temp": args.prior_temp}
    net = NetConfig(hidden=args.hidden, fusion=args.fusion, sff=not args.no_sff, **prior).as_dict()
    cfg = TrainConfig(episodes=args.episodes, batch=args.batch, lr=args.lr, seed=args.seed,
                      use_global=not args.no_global, aux=not args.no_aux, net=net, teacher=args.teacher,
                      imitate=args.imitate, init=args.init or "", dataset=args.dataset, guard=args.guard,
                      repair_reward=args.repair_reward)
    out = Path(args.out)
    ckpt = train(cfg, out)
    runs = {"with global state": out / "train.csv"} | ({"without": Path(args.compare) / "train.csv"}
                                                        if args.compare else {})
    png = plot_curves(runs, out / "curves.png")
    export_weights(ckpt, out / "plan2place.npz")
    print(f"checkpoint: {ckpt}  log: {out / 'train.csv'}  curves: {png}")
    print(f"ship it: cp {out / 'plan2place.npz'} models/weights/plan2place/")
    return 0


def cmd_bench(args) -> int:
    from app.bench import run_benchmark
    try:
        return run_benchmark(args.what, args)
    except FileNotFoundError as e:  # a path given on the command line (a run, an adapter)
        raise BadInput(f"{e.filename}: {e.strerror}") from e


def _parser_options(p: argparse.ArgumentParser) -> None:
    """The instruction parser's options, shared by `parse` and `generate`."""
    p.add_argument("--parser", choices=["combined", "rules", "lora", "openai"], default=None,
                   help="instruction parser (default: combined = rules + the LoRA language model, the rules "
                   "alone if it cannot load; or H3DS_PARSER)")
    p.add_argument("--openai-url", default=None, help="--parser openai: the server's base URL, e.g. "
                   "http://127.0.0.1:8000/v1 (or H3DS_OPENAI_BASE_URL)")
    p.add_argument("--openai-model", default=None, help="--parser openai: the served model's name")
    p.add_argument("--policy", choices=POLICIES, default=None, help=f"--parser combined: how the rules and the model "
                   f"are combined (default {DEFAULT_POLICY}; models/language/combined.py)")


def build_parser() -> argparse.ArgumentParser:
    room_help = f"one of: {', '.join(ROOM_TYPES)} (any case; living_room works too)"
    ap = Parser(prog="h3ds", description="Turn a household instruction into an AI2-THOR scene for a robot and a "
                "VR user.", epilog=EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True, parser_class=Parser)

    p = sub.add_parser("parse", help="instruction -> task scene graph (JSON on stdout)")
    p.add_argument("instruction", nargs="?", help='e.g. "Put a chilled bread on the counter"')
    p.add_argument("--room-type", help=f"the room the task happens in; inferred when left out ({room_help})")
    p.add_argument("--json", action="store_true", help="JSON output (the default; kept for scripts)")
    p.add_argument("--batch", metavar="IN.jsonl", help='many instructions, one {"id", "instruction", '
                   '"room_type"?} per line')
    p.add_argument("--out", metavar="OUT.jsonl", help="with --batch: write here instead of stdout")
    _parser_options(p)
    p.set_defaults(run=cmd_parse)

    p = sub.add_parser("place", help="place the objects of constraint plan(s) -> layout JSON", epilog=SOLVER_LIST,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("plans", nargs="+", metavar="PLAN.json")
    p.add_argument("--solver", default=None, help=SOLVER_HELP)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", metavar="LAYOUT.json", help="write the layout here instead of stdout")
    p.add_argument("--out-dir", metavar="DIR", help="for several plans: DIR/<plan id>.json each")
    p.add_argument("--steps", metavar="STEPS.jsonl", help="one plan: each placement step as a JSON line, written as "
                   "the placer goes (pose, energy terms, a repair's reason, the best-scored candidates); - for stdout")
    p.add_argument("--keep", metavar="LAYOUT.json", help="one plan: keep the poses of this layout's placements "
                   "(e.g. a layout edited by hand, with the objects to place again deleted) and place the rest "
                   "around them")
    p.set_defaults(run=cmd_place)

    p = sub.add_parser("generate", help="the whole pipeline -> task_graph, plan, layout, house JSON and GLB",
                       epilog=SOLVER_LIST, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("instruction")
    p.add_argument("--room-type", required=True, help=room_help + "; infer (read from the instruction); or apartment "
                   "(several rooms joined by doors)")
    p.add_argument("--rooms", default=None, help='with --room-type apartment: the rooms, e.g. "kitchen, living room, '
                   'bedroom, bathroom" (at most 8; default: 2-5 rooms chosen from the task and the seed)')
    p.add_argument("--seed", type=int, default=0, help="same seed, same scene")
    p.add_argument("--solver", default=None, help=SOLVER_HELP)
    p.add_argument("--out", required=True, metavar="DIR")
    _parser_options(p)
    p.set_defaults(run=cmd_generate)

    add_scene_commands(sub, SOLVER_HELP, SOLVER_LIST)

    p = sub.add_parser("studio", help="the browser studio and its HTTP API (prints the URLs)")
    p.add_argument("--host", default="127.0.0.1", help="address to listen on (0.0.0.0 for other machines)")
    p.add_argument("--port", type=int, default=8080, help="studio port; if busy, the next free one is used")
    p.add_argument("--api-port", type=int, default=None, help="HTTP API port (default: studio port + 1)")
    p.add_argument("--simulated-headset", action="store_true",
                   help="also start the headset simulator (a stand-in for the Quest app) and pair it")
    p.set_defaults(run=cmd_studio)

    p = sub.add_parser("feedback", help="glove feedback from headsets: export for retraining")
    fb = p.add_subparsers(dest="feedback_command", required=True)
    e = fb.add_parser("export", help="one JSON record per glove event, joined with its scene version and task graph")
    e.add_argument("--format", choices=["jsonl"], default="jsonl")
    e.add_argument("--since", default=None, help="received at or after this ISO time (UTC if no zone)")
    e.add_argument("--until", default=None, help="received before this ISO time")
    e.add_argument("--scene", type=int, default=None, help="only this stored scene id")
    e.add_argument("--session", default=None, help="only this headset session")
    e.add_argument("--out", default=None, help="file to write (default: stdout)")
    e.set_defaults(run=cmd_feedback_export)

    p = sub.add_parser("demo", help="generate the demo scene (bread on the counter) into a folder")
    p.add_argument("--out", default="out/demo", metavar="DIR")
    p.set_defaults(run=cmd_demo)

    p = sub.add_parser("bench", help="benchmarks that print figures (placement, plan2place, language, studio, ...)")
    p.add_argument("what", choices=["parser", "generate", "placement", "energy", "studio", "language", "vrpose",
                                          "plan2place", "bridge", "batch", "steps"])
    p.add_argument("--n", type=int, default=30, help="instructions (generate) or plans (placement) to run")
    p.add_argument("--split", default="valid_unseen", help="ALFRED split to score (parser)")
    p.add_argument("--room-type", default=None, choices=["apartment"], help="generate: apartments instead of "
                   "one room per instruction")
    p.add_argument("--rooms", default=None, help="generate --room-type apartment: the same rooms for every "
                   "instruction (default: drawn from each task)")
    p.add_argument("--dataset", default="seen", choices=["seen", "unseen_a", "unseen_b", "dense", "human", "varied"],
                   help="placement, steps: which constraint dataset (plan2place only: varied, the checkpoint-choice plans)")
    p.add_argument("--solvers", default=None, help="comma-separated solver names; placement: default dfs,milp,z3,greedy,plan2place; "
                   "generate: default dfs and the default solver")
    p.add_argument("--seeds", type=int, default=5, help="placement, steps: seeds per plan")
    p.add_argument("--budget", type=float, default=None, help="placement: time budget per plan (s)")
    p.add_argument("--update", action="store_true", help="placement: run only --solvers again and keep the other "
                   "solvers' rows stored in --out (same --dataset, --n and --seeds)")
    p.add_argument("--out", default=None, help="placement, language: folder for results and plots")
    p.add_argument("--adapter", default=None, metavar="DIR", help="language: the LoRA adapter to measure "
                   "(default: the shipped one)")
    p.add_argument("--sets", default=None, help="language: comma-separated evaluation sets (default: all)")
    p.add_argument("--per-set", type=int, default=0, help="language: instructions per set (0: all)")
    p.add_argument("--decoding", type=int, default=0, metavar="N", help="language: also compare constrained "
                   "decoding with free decoding + MiniLM snapping on N ID instructions")
    p.add_argument("--n-slow", type=int, default=18, help="vrpose: scenes also placed by the slower solvers")
    p.add_argument("--runs", default=None, help="plan2place: comma-separated checkpoints or training folders "
                   "(default: the shipped weights)")
    _executor_options(p, "placement: worker processes (default: this process)")
    p.set_defaults(run=cmd_bench)

    p = sub.add_parser("train", help="train a model (seeded, resumable, loss curves): language, roles, placement")
    train = p.add_subparsers(dest="what", required=True, parser_class=Parser)
    t = train.add_parser("language", help="LoRA fine-tuning of f_theta1 (instruction -> compact task graph)")
    t.add_argument("--out", default="runs/language", metavar="DIR", help="checkpoints, loss.csv, loss.png, adapter/")
    t.add_argument("--base", default="smollm2-135m-instruct", help="the bundled SmolLM2-135M-Instruct, or any "
                   "Hugging Face causal LM folder (e.g. a local Falcon-7B)")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--epochs", type=float, default=1.0)
    t.add_argument("--max-steps", type=int, default=None, help="stop after N optimiser steps (overrides --epochs)")
    t.add_argument("--batch-size", type=int, default=16)
    t.add_argument("--lr", type=float, default=1e-3)
    t.add_argument("--warmup", type=int, default=20, help="linear warm-up steps (then cosine to 10 %%)")
    t.add_argument("--init-adapter", default=None, metavar="DIR", help="continue training this adapter (e.g. "
                   "models/weights/lora; its LoRA settings, not --lora-*)")
    t.add_argument("--augment", action="store_true", help="train on the rows the shipped adapter trained on, each "
                   "as it is plus its object-shift (training pool of rare types) and text-shift versions (a "
                   "training seed of their own); the policy, confirmation and evaluation rows stay unseen")
    t.add_argument("--lora-r", type=int, default=16, help="the paper: 32")
    t.add_argument("--lora-alpha", type=float, default=21.5, help="the paper: 43")
    t.add_argument("--lora-dropout", type=float, default=0.05, help="the paper: 0.05")
    t.add_argument("--lora-layers", type=int, default=15, help="LoRA on the top N blocks (0: all)")
    t.add_argument("--save-every", type=int, default=100, help="checkpoint and held-out check every N steps")
    t.add_argument("--limit", type=int, default=None, help="train on the first N examples only")
    t.add_argument("--threads", type=int, default=None, help="torch CPU threads")
    t.set_defaults(run=cmd_train_language)
    t = train.add_parser("placement", help="actor-critic training of Plan2Place on the seen training instructions")
    t.add_argument("--out", default="runs/placement", metavar="DIR", help="checkpoint.pt, train.csv, curves.png")
    t.add_argument("--episodes", type=int, default=2000)
    t.add_argument("--batch", type=int, default=4, help="episodes per update")
    t.add_argument("--lr", type=float, default=3e-4)
    t.add_argument("--teacher", type=int, default=0, metavar="N", help="policy advantages from greedy completions "
                   "of the N lowest-energy candidates and the sampled one per step (not in the paper; 0: off)")
    t.add_argument("--imitate", type=float, default=0.0, metavar="W", help="with --teacher: weight of the "
                   "cross-entropy towards the judged candidate of lowest final energy (not in the paper; 0: off)")
    t.add_argument("--init", default=None, metavar="NPZ", help="start from exported weights (plan2place.npz)")
    t.add_argument("--dataset", default="seen", choices=["seen", "varied"], help="the seen training split, or "
                   "its instructions replanned per episode in rooms of random size and density (not in the paper)")
    t.add_argument("--guard", action="store_true", help="sample with the reach guard as an action mask, as the "
                   "solver places (not in the paper)")
    t.add_argument("--repair-reward", action="store_true", help="the return after the repairs that every solved "
                   "layout gets (the last step's reward takes their change of the energy; not in the paper)")
    t.add_argument("--prior-temp", type=float, default=None,
                   help="temperature of the actor's immediate-energy prior (default 0.05; 0: none)")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--hidden", type=int, default=128)
    t.add_argument("--fusion", choices=["cross", "self", "concat"], default="cross")
    t.add_argument("--no-sff", action="store_true", help="ablation: the critic without semantic features")
    t.add_argument("--no-aux", action="store_true", help="ablation: without the auxiliary loss")
    t.add_argument("--no-global", action="store_true", help="ablation: the global state s_g zeroed")
    t.add_argument("--compare", metavar="DIR", help="another run (e.g. --no-global) for the E_rel figure")
    t.set_defaults(run=cmd_train_placement)
    t = train.add_parser("roles", help="f_theta2: MiniLM (frozen, or --lora) + two-layer role head on id_train")
    t.add_argument("--out", default="runs/roles", metavar="DIR",
                   help="features/, checkpoint.pt, train.csv, curves.png, head.pt")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--epochs", type=int, default=40)
    t.add_argument("--lr", type=float, default=1e-3)
    t.add_argument("--batch-size", type=int, default=256)
    t.add_argument("--limit", type=int, default=1200, help="id_train rows, a seeded sample (0: all 10,786)")
    t.add_argument("--eval-limit", type=int, default=250, help="id_eval rows for the held-out curve (0: all)")
    t.add_argument("--lora", action="store_true",
                   help="train LoRA adapters on the encoder with the head (the run folder then loads as the model)")
    t.add_argument("--lora-lr", type=float, default=5e-4, help="the adapters' learning rate (with --lora)")
    t.set_defaults(run=cmd_train_roles)

    p = sub.add_parser("data", help="rebuild the bundled constraint datasets (deterministic)")
    p.add_argument("what", choices=["build"])
    _executor_options(p, "worker processes, one dataset each (default: this process)")
    p.set_defaults(run=cmd_data)

    p = sub.add_parser("batch", help="many scenes from a JSONL file, on local processes or Ray (resumable)")
    batch = p.add_subparsers(dest="batch_command", required=True, parser_class=Parser)
    b = batch.add_parser("generate", help='one scene per line {"instruction", "room_type", "seed"?, "solver"?, '
                         '"id"?}: the five files of `generate` each, plus results.jsonl')
    b.add_argument("input", metavar="IN.jsonl")
    b.add_argument("--out", required=True, metavar="DIR", help="scenes/<id>/ and results.jsonl; a re-run skips "
                   "the scenes already complete here")
    b.add_argument("--parser", choices=["combined", "rules", "lora"], default=None,
                   help="instruction parser (default: the pipeline's)")
    b.add_argument("--no-progress", action="store_true", help="no progress bar")
    b.add_argument("--studio", action="store_true", help="also store every scene in the studio's database "
                   "(DATABASE_URL or the studio's SQLite file), to browse the batch in the Scenes tab")
    _executor_options(b, "worker processes (default: one per CPU; on Ray: the cluster's CPUs)")
    b.set_defaults(run=cmd_batch_generate)
    return ap


def _executor_options(p, workers_help: str) -> None:
    p.add_argument("--workers", type=int, default=None, metavar="N", help=workers_help)
    p.add_argument("--ray", action="store_true", help="run on Ray: a local Ray started here, or the cluster at "
                   "RAY_ADDRESS")
    p.add_argument("--ray-address", default=None, metavar="ADDRESS", help="join this Ray cluster (e.g. "
                   "ray://head:10001, or auto on a cluster node)")


def main(argv: list[str] | None = None) -> int:
    try:
        args = build_parser().parse_args(argv)
        return args.run(args)
    except (BadInput, InputError) as e:
        print(f"h3ds: error: {e}", file=sys.stderr)
        return 2
    except ValidationError as e:
        print(f"h3ds: error: {value_error('input', e, 'input')}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
