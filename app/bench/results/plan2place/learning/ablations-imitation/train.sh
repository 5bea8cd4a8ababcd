#!/usr/bin/env bash
# ablations under the imitation set-up, one reduced budget: 400 episodes from the initial weights, seed 0
cd "$(dirname "$0")/.."
common="--teacher 6 --imitate 1.0 --lr 1e-3 --episodes 400"
q1() { for a in "cross" "concat --fusion concat" "self --fusion self"; do set -- $a; n=$1; shift
  nice .venv/bin/h3ds train placement --out runs/abl-im-$n $common "$@" > runs/abl-im-$n.log 2>&1; done; }
q2() { for a in "noaux --no-aux" "nosff --no-sff" "h64 --hidden 64"; do set -- $a; n=$1; shift
  nice .venv/bin/h3ds train placement --out runs/abl-im-$n $common "$@" > runs/abl-im-$n.log 2>&1; done; }
q1 & q2 & wait
echo DONE
