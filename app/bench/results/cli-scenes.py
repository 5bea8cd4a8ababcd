"""What the scene-folder commands cost from a shell, against `h3ds generate` of the same scene in the same run: each
is a fresh `h3ds` process (start-up included, as a script pays it), on a single kitchen and on a three-room apartment,
with its own SQLite database. `edit --edits` makes MOVES moves from one file in one run, against MOVES runs of
`edit --move` (MOVES x its p50). N rounds; p50 seconds of wall time. Run from a tree's root:
PYTHONPATH=. python app/bench/results/cli-scenes.py > app/bench/results/cli-scenes.txt
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

N = 5
MOVES = 3  # the moves of `edit --edits`
H3DS = [sys.executable, "-m", "app.cli"]
BREAD = "Put a chilled bread on the counter"
CASES = {"kitchen": (["--room-type", "kitchen"], "fridge-0", []),
         "apartment": (["--room-type", "apartment", "--rooms", "kitchen, living room, bedroom"], "r1-fridge-0",
                       ["--room", "1"])}


def timed(args: list[str], env: dict) -> float:
    t0 = time.perf_counter()
    subprocess.run(H3DS + args, check=True, capture_output=True, env=env)
    return time.perf_counter() - t0


def one_round(case: str, tmp: Path, k: int, env: dict) -> dict[str, float]:
    room, fridge, which = CASES[case]
    folder, back = tmp / f"{case}-{k}", tmp / f"{case}-{k}-back"
    out = {"generate": timed(["generate", BREAD, *room, "--seed", str(k), "--out", str(folder)], env)}
    out["edit --move"] = timed(["edit", str(folder), *which, "--move", fridge, "1.0", "1.0"], env)
    edits = tmp / f"{case}-{k}-edits.json"
    edits.write_text(json.dumps([{"kind": "move", "object": fridge, "x": 1.0 + 0.2 * m, "z": 1.0}
                                 for m in range(MOVES)]))
    out[f"edit --edits ({MOVES} moves)"] = timed(["edit", str(folder), *which, "--edits", str(edits)], env)
    out["scenes store"] = timed(["scenes", "store", str(folder), "--name", f"{case} {k}"], env)
    out["scenes export"] = timed(["scenes", "export", "1", "--out", str(back)], env)
    return out


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "DATABASE_URL": f"sqlite:///{tmp}/bench.db", "H3DS_PARSER": "rules"}
        timed(["generate", BREAD, "--room-type", "kitchen", "--out", f"{tmp}/warm"], env)  # not timed: warms caches
        print(f"{N} rounds, a fresh h3ds process each (rule parser, plan2place); p50 s of wall time, "
              "x: / generate's p50")
        for case in CASES:
            runs = [one_round(case, Path(tmp), k, env) for k in range(N)]
            gen = statistics.median(r["generate"] for r in runs)
            p50 = {what: statistics.median(r[what] for r in runs) for what in runs[0]}
            cells = [f"{what} {p50[what]:.2f} ({p50[what] / gen:.2f} x)" for what in p50 if what != "generate"]
            print(f"  {case:10s} generate {gen:.2f}   " + "   ".join(cells))
            many, one = p50[f"edit --edits ({MOVES} moves)"], p50["edit --move"]
            print(f"  {case:10s} {MOVES} moves: edit --edits {many:.2f} against {MOVES} x edit --move "
                  f"{MOVES * one:.2f} ({many / (MOVES * one):.2f} x)")


if __name__ == "__main__":
    main()
