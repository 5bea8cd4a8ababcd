#!/usr/bin/env bash
# The two runs of decision.md, each in stages of 500 episodes (resumed from its checkpoint), the weights exported
# after each stage: runs/repair-reward/{repair,control}/ep-{500,1000,1500,2000}.npz. Run from the repository root.
set -euo pipefail
run() {  # name, extra options
  local out=runs/repair-reward/$1
  for n in 500 1000 1500 2000; do
    [ -f "$out/ep-$n.npz" ] && continue
    .venv/bin/h3ds train placement --out "$out" --episodes $n --init models/weights/plan2place/plan2place.npz \
      --teacher 0 --guard --lr 1e-4 --batch 4 --seed 0 "${@:2}" > "$out.log" 2>&1
    cp "$out/plan2place.npz" "$out/ep-$n.npz"
  done
}
mkdir -p runs/repair-reward
run repair --repair-reward & run control & wait
