#!/usr/bin/env bash
# every ablation of train.sh (and the hidden-256 run) with training seed $1, the same recipe and budget (400 episodes
# from the initial weights), into runs/abl-im-s$1-<name>: two seeds of each configuration, judged in one bench run
# (bench-seeds.sh), show how far seeds lie apart. Run from the repository's root: bash .../train-seeds.sh 1
seed=${1:?training seed}
common="--teacher 6 --imitate 1.0 --lr 1e-3 --episodes 400 --seed $seed"
run() { n=$1; shift; nice .venv/bin/h3ds train placement --out runs/abl-im-s$seed-$n $common "$@" \
  > runs/abl-im-s$seed-$n.log 2>&1; }
mkdir -p runs
(run cross; run concat --fusion concat; run self --fusion self; run h64 --hidden 64) &
(run noaux --no-aux; run nosff --no-sff; run h256 --hidden 256) &
wait
echo DONE
