#!/usr/bin/env bash
# Records `needlesim-server simulate` on every shipped scene (server/scenes/*.toml) with a given
# binary: one CSV per scene in OUT_DIR, and OUT_DIR/manifest.txt with each CSV's sha256, row
# count and the run's last stderr line. Before a change that should not move the physics (issue
# 32, one simulation for both dimensions), record with the old binary, then with the new one, and
# compare the manifests (bit-identical) or the CSVs (compare.py-style tolerances) scene by scene.
# Scenes with no trajectory of their own get the straight insertion in trajectories/; planning
# inputs (*-plan.toml) are skipped. Runs keep unconverged ticks (marked in the CSV) so that a
# scene whose run would stop records its whole behaviour.
#
#   tests/baselines/record.sh BINARY OUT_DIR
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${1:?usage: record.sh BINARY OUT_DIR}"
out="${2:?usage: record.sh BINARY OUT_DIR}"
mkdir -p "$out"
: > "$out/manifest.txt"
record() { # SCENE ARGS...: one run, one line of the manifest
    local scene="$1" start status secs sum rows
    shift
    start=$(date +%s.%N)
    if "$bin" simulate "$@" --keep-unconverged -o "$out/$scene.csv" 2> "$out/$scene.log"; then
        status=ok
    else
        status="failed($?)"
    fi
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    sum=$( [ -f "$out/$scene.csv" ] && sha256sum "$out/$scene.csv" | cut -c1-64 || echo none)
    rows=$( [ -f "$out/$scene.csv" ] && wc -l < "$out/$scene.csv" || echo 0)
    printf '%s %s %s rows=%s wall_s=%.1f\n' "$scene" "$status" "$sum" "$rows" "$secs" | tee -a "$out/manifest.txt"
}
# The shipped examples by name (2D examples' trajectories are built in), the others by path with
# a trajectory from trajectories/; the *-toughness scenes (second pass) replay their base scene's
# recorded poses (its CSV's first four columns: t_s,x_m,y_m,theta_rad).
for toml in "$repo"/server/scenes/*.toml; do
    scene="$(basename "$toml" .toml)"
    case "$scene" in
        *-plan) printf '%s skipped: a planning input (needlesim-server plan)\n' "$scene" | tee -a "$out/manifest.txt" ;;
        *-toughness) ;;
        *) if [ -f "$repo/tests/baselines/trajectories/$scene.csv" ]; then
               record "$scene" --scene "$toml" --trajectory "$repo/tests/baselines/trajectories/$scene.csv"
           else
               record "$scene" --scene "$scene"
           fi ;;
    esac
done
for toml in "$repo"/server/scenes/*-toughness.toml; do
    scene="$(basename "$toml" .toml)"
    base="${scene%-toughness}"
    cut -d, -f1-4 "$out/$base.csv" > "$out/$scene.trajectory.csv"
    record "$scene" --scene "$toml" --trajectory "$out/$scene.trajectory.csv"
done
# simulate-24c3687.txt: the manifest of main at 24c3687 (before issue 32), recorded with its dev
# build (the numeric crates optimised) on 2026-11-28; a second run gave the same sha256s (the
# offline runs are deterministic).
