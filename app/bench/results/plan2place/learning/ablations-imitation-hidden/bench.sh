#!/usr/bin/env bash
# hidden 64 / 128 / 256 under the imitation set-up (400 episodes each), judged with the repairs and the polish
cd "$(dirname "$0")/.."
runs=runs/abl-im-cross,runs/abl-im-h64,runs/abl-im-h256
R=app/bench/results/plan2place/learning/ablations-imitation-hidden
one() { .venv/bin/h3ds bench plan2place --dataset $1 --n $2 --seeds 3 --runs $runs --out $R/$1 > runs/abl-hidden-$1.log 2>&1; }
one seen 40 & (one unseen_a 20; one dense 20) & wait
echo DONE
