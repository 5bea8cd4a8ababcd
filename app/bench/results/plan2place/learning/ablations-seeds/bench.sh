#!/usr/bin/env bash
# the ablations of both training seeds (train-seeds.sh 0 and 1 in ablations-imitation/) in one bench run per set,
# every placer with the repairs; then summary.py. Run from the repository's root.
R=app/bench/results/plan2place/learning/ablations-seeds
runs=$(for s in 0 1; do for c in cross concat self noaux nosff h64 h256; do printf 'runs/abl-im-s%s-%s,' $s $c; done; done)
one() { .venv/bin/h3ds bench plan2place --dataset $1 --n $2 --seeds 3 --runs ${runs%,} --out $R/$1 > runs/abl-seeds-$1.log 2>&1; }
one seen 40 & (one unseen_a 20; one dense 20) & wait
PYTHONPATH=. .venv/bin/python $R/summary.py > /dev/null
echo DONE
