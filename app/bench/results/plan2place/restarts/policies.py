"""How many solves from another random state to make, replayed from `tries.py`'s record (`tries-dense.json`), without
solving again: at most R tries (`full`: the whole solve; `no_reorder`: without its broken-first solve; `cheap`:
steps and repairs only), stopping at the first kept
one or going on while an object is still left out; a try is kept by models.placement.restarts' rule. Prints the
objects placed (CNT, x 100) and energy against no restart, and the time against no restart (mean, and the median
run); written to `policies.txt`:

    python app/bench/results/plan2place/restarts/policies.py > app/bench/results/plan2place/restarts/policies.txt
"""
import json
import statistics
from pathlib import Path

ROWS = json.loads((Path(__file__).parent / "tries-dense.json").read_text())


def better(new: dict, old: dict) -> bool:
    return new["placed"] >= old["placed"] and new["out"] <= old["out"] and new["E"] < old["E"]


def replay(kind: str, most: int, go_on: bool) -> str:
    kept, cnt, energy, times = 0, 0.0, 0.0, []
    for r in ROWS:
        base = best = r["base"]
        t = r["t0"]
        for tried in r[kind][:most]:
            if not best["failed"]:
                break
            t += tried["t"]
            if better(tried, best):
                best, kept = tried, kept + 1
                if not go_on:
                    break
        cnt += (best["placed"] - base["placed"]) / (base["placed"] + base["failed"])
        energy += best["E"] - base["E"]
        times.append((r["t0"], t))
    n = len(ROWS)
    mean = sum(t for _, t in times) / sum(t for t, _ in times)
    med = statistics.median(t for _, t in times) / statistics.median(t for t, _ in times)
    return (f"| {kind} | {most} | {'yes' if go_on else 'no'} | {kept} | {100 * cnt / n:+.2f} | {energy / n:+.3f} | "
            f"{mean:.2f} | {med:.2f} |")


if __name__ == "__main__":
    print(f"{len(ROWS)} `dense` diagnosis runs, {sum(bool(r['full']) for r in ROWS)} with an object left out\n")
    print("| tries | at most | go on after a kept one | kept | CNT | energy | time x (mean) | median run x |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for kind in ("full", "no_reorder", "cheap"):
        for most in (1, 2, 3):
            for go_on in (False, True):
                print(replay(kind, most, go_on))
