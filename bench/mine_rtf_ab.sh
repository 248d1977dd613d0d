#!/usr/bin/env bash
# Interleaved A/B of bench/mine_rtf.py between two built checkouts (the machine is shared: A and B alternate so
# that both see the same load). Each run is one `mine_rtf.py --robots N` in a fresh shell sourcing that
# checkout's scripts/env.sh with its workspace; prints one JSON line per run, prefixed by A or B.
#   bash bench/mine_rtf_ab.sh <repo A> <workspace A> <repo B> <workspace B> [rounds 3] [robots 1] [sim seconds 300]
set -euo pipefail
repo_a=$1 ws_a=$2 repo_b=$3 ws_b=$4
rounds=${5:-3} robots=${6:-1} seconds=${7:-300}
venv=${UNEXMIN_VENV:-$ws_b/venv}
run() {  # label repo ws
  (cd "$2" && export UNEXMIN_WS="$3" UNEXMIN_VENV="$venv" && source scripts/env.sh &&
    echo "$1 load=$(cut -d' ' -f1 /proc/loadavg) $(python bench/mine_rtf.py --robots "$robots" --sim-seconds "$seconds")")
}
for _ in $(seq "$rounds"); do
  run A "$repo_a" "$ws_a"
  run B "$repo_b" "$ws_b"
done
