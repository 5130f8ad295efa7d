#!/usr/bin/env bash
# The paper-scale runs committed under docs/report/paper-scale/, made from a clean checkout so
# that each provenance.json names the commit ("dirty": false):
#
#   paper-escape-1e8          the paper's escape problem, 10^8 starts per hole, joint (n, t)
#   paper-transport-1e8       the paper's transport problem, 10^8 starts per entry hole and width
#   escape-tail-phi_c=0-1e9   the island hole at phi_c = 0 alone, 10^9 starts
#   escape-tail-phi_c=1-1e9   the island hole at phi_c = 1 alone, 10^9 starts
#
# Usage, from the repository root of a clean checkout on a quiet machine:
#
#   scripts/paper_scale_runs.sh [NAME ...]     # default: all four, in the order above
#
# Each run goes into the ignored folder runs/ (so that it does not dirty the tree for the next
# one), with --require-clean; a run stopped by Ctrl-C or a crash is continued by running the
# script again (--resume). Each finished run is audited by `bouncer verify`, then copied over
# its folder in docs/report/paper-scale/. Committing them is left to you:
#
#   git add docs/report/paper-scale && git commit
#
# Scene files: docs/report/paper-scale/scenes/. Time on 2 quiet cores, from the committed 10^8
# runs (18.7e6 collisions/s; paper-escape 925 s, paper-transport 878 s of compute) and the
# collisions per start of each island hole alone (32.7 at phi_c = 0, 34.6 at phi_c = 1, from
# 2x10^5 starts): about 16, 15, 29 and 31 minutes, plus ~1 minute of `bouncer verify` each and
# a minute to compile the kernels with the joint record once. Disk: 6-10 MB a run (the
# verification sample dominates; joint.csv ~0.3-0.5 MB).
set -euo pipefail

SCENES=docs/report/paper-scale/scenes
DEST=docs/report/paper-scale
declare -A SCENE=(
  [paper-escape-1e8]="$SCENES/paper-escape.toml 100000000"
  [paper-transport-1e8]="$SCENES/paper-transport.toml 100000000"
  [escape-tail-phi_c=0-1e9]="$SCENES/escape-tail-phi_c=0.toml 1000000000"
  [escape-tail-phi_c=1-1e9]="$SCENES/escape-tail-phi_c=1.toml 1000000000"
)
ORDER=(paper-escape-1e8 paper-transport-1e8 escape-tail-phi_c=0-1e9 escape-tail-phi_c=1-1e9)

if [ -n "$(git status --porcelain)" ]; then
  echo "paper_scale_runs.sh: the work tree has changes (git status): commit or stash them first" >&2
  exit 2
fi

names=("$@")
[ ${#names[@]} -gt 0 ] || names=("${ORDER[@]}")
for name in "${names[@]}"; do
  [ -n "${SCENE[$name]:-}" ] || { echo "paper_scale_runs.sh: no run named $name" >&2; exit 2; }
done

for name in "${names[@]}"; do
  read -r scene particles <<<"${SCENE[$name]}"
  out="runs/$name"
  resume=()
  [ -f "$out/manifest.json" ] && resume=(--resume)
  bouncer run "$scene" --particles "$particles" --out "$out" --require-clean "${resume[@]}"
  bouncer verify "$out"
done

for name in "${names[@]}"; do
  rm -rf "${DEST:?}/$name"
  mkdir -p "$DEST/$name"
  for file in runs/"$name"/*; do
    cp "$file" "$DEST/$name/"
  done
  echo "copied runs/$name to $DEST/$name"
done
