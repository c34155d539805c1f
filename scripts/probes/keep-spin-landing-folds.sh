#!/bin/bash
# Probe for docs/physics.md, "Keeping a body's spin through its sticks": how often the seed ragdoll
# of stability/large-dt-ragdoll-15.xml (dt 1/15 s) ends with a box folded (a corner turned inside out
# through its three neighbours, which its sticks then hold: the run's final stick error over the
# suite's 3%) with keepSpin off and on, over 24 drops from other orientations (euler 70 + a, 20 + b,
# 10; a = 0 to 200 by 40, b = 0 to 90 by 30), 150 steps each. The drop is chaotic: one drop, as the
# suite runs, says little. Not part of the build. From the repository's root, after
# `cmake --build --preset release --target lab`:
#
#   scripts/probes/keep-spin-landing-folds.sh build/release/app/lab/lab 10 4 [METHOD]
#   VERBOSE=1 scripts/probes/keep-spin-landing-folds.sh ...   # each drop's final stick error too
set -euo pipefail
lab=$1 iterations=$2 substeps=$3 method=${4:-gauss-seidel}
scene=assets/scenes/stability/large-dt-ragdoll-15.xml
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
finalStickError() {
  "$lab" run "$1" --methods "$method" --iterations "$iterations" --substeps "$substeps" --steps 150 --json |
    python3 -c "import json, sys; print(json.load(sys.stdin)['max_constraint_error'])"
}
folded() { python3 -c "import sys; sys.exit(0 if $1 > 0.03 else 1)"; }
drops=0 off=0 on=0
for a in 0 40 80 120 160 200; do
  for b in 0 30 60 90; do
    for keep in off on; do
      sed -e "s/euler=\"70 20 10\"/euler=\"$((70 + a)) $((20 + b)) 10\"/" \
        -e "s/<solver /<solver keep-spin=\"$keep\" /" "$scene" >"$dir/$keep.xml"
    done
    e0=$(finalStickError "$dir/off.xml")
    e1=$(finalStickError "$dir/on.xml")
    drops=$((drops + 1))
    if folded "$e0"; then off=$((off + 1)); fi
    if folded "$e1"; then on=$((on + 1)); fi
    if [ -n "${VERBOSE:-}" ]; then echo "euler $((70 + a)) $((20 + b)) 10: off $e0, on $e1"; fi
  done
done
echo "$method $iterations x $substeps: a box folded at the end in $off of $drops drops without keepSpin, $on with it"
