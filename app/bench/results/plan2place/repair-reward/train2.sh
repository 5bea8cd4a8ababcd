#!/usr/bin/env bash
# decision2.md's candidates: round 1's `repair` run resumed to 4,000 episodes, and a seed-1 run to 2,000; weights
# exported every 500 episodes as runs/repair-reward/<run>-ep-<n>.npz. Run from the repository root.
set -euo pipefail
run() {  # name, seed, first, last
  local out=runs/repair-reward/$1
  for n in $(seq "$3" 500 "$4"); do
    [ -f "runs/repair-reward/$1-ep-$n.npz" ] && continue
    .venv/bin/h3ds train placement --out "$out" --episodes "$n" --init models/weights/plan2place/plan2place.npz \
      --teacher 0 --guard --repair-reward --lr 1e-4 --batch 4 --seed "$2" > "$out.log" 2>&1
    cp "$out/plan2place.npz" "runs/repair-reward/$1-ep-$n.npz"
  done
}
run repair 0 2500 4000 & run repair-s1 1 500 2000 & wait
