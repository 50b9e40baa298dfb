#!/usr/bin/env bash
# Records `needlesim-server simulate` on every shipped scene (server/scenes/*.toml) with a given
# binary: one CSV per scene in OUT_DIR, and OUT_DIR/manifest.txt with each CSV's sha256, row
# count and the run's last stderr line. Before a change that should not move the physics (issue
# 32, one simulation for both dimensions), record with the old binary, then with the new one, and
# compare the manifests (bit-identical) or the CSVs (compare.py-style tolerances) scene by scene.
# Scenes with no trajectory of their own get the straight insertion in trajectories/; planning
# inputs (*-plan.toml) are skipped.
#
#   tests/baselines/record.sh BINARY OUT_DIR
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${1:?usage: record.sh BINARY OUT_DIR}"
out="${2:?usage: record.sh BINARY OUT_DIR}"
mkdir -p "$out"
: > "$out/manifest.txt"
for toml in "$repo"/server/scenes/*.toml; do
    scene="$(basename "$toml" .toml)"
    case "$scene" in
        *-plan) printf '%s skipped: a planning input (needlesim-server plan)\n' "$scene" | tee -a "$out/manifest.txt"; continue ;;
    esac
    # Scenes without a trajectory of their own get a straight insertion (trajectories/).
    traj=()
    [ -f "$repo/tests/baselines/trajectories/$scene.csv" ] && traj=(--trajectory "$repo/tests/baselines/trajectories/$scene.csv")
    start=$(date +%s.%N)
    if "$bin" simulate --scene "$toml" "${traj[@]}" -o "$out/$scene.csv" 2> "$out/$scene.log"; then
        status=ok
    else
        status="failed($?)"
    fi
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    sum=$( [ -f "$out/$scene.csv" ] && sha256sum "$out/$scene.csv" | cut -c1-64 || echo none)
    rows=$( [ -f "$out/$scene.csv" ] && wc -l < "$out/$scene.csv" || echo 0)
    printf '%s %s %s rows=%s wall_s=%.1f\n' "$scene" "$status" "$sum" "$rows" "$secs" | tee -a "$out/manifest.txt"
done
