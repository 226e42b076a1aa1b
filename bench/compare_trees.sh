#!/usr/bin/env bash
# identify + diagnose on one simulated log, this tree's `tpf` against an earlier revision's, in
# one run (alternating, so both see the same machine). Release builds of both; the earlier one is
# built in build/compare-<rev> from a worktree at build/compare-src, both kept so that the next
# run only rebuilds what changed (`git worktree remove build/compare-src` drops the worktree).
#
#   bench/compare_trees.sh <revision> [log seconds = 3600] [repetitions = 2]
#
# Prints the wall and CPU seconds of identify + diagnose per repetition and tree, the
# medians and new/old ratios, then what each tree's identify and diagnose printed (the figures).
# The log: data/scenarios/excitation-undeclared.json (the 4-joint arm with undeclared effects,
# seed 3), simulated by this tree's `tpf`.
set -euo pipefail
rev=${1:?usage: bench/compare_trees.sh <revision> [log seconds] [repetitions]}
seconds=${2:-3600}
reps=${3:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
old_src="$root/build/compare-src"
old_build="$root/build/compare-$(git -C "$root" rev-parse --short "$rev")"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "compare: building this tree's tpf (Release)"
(cd "$root" && cmake --preset release >/dev/null)
cmake --build "$root/build/release" --target tpf -j2 >/dev/null
echo "compare: building tpf at $rev (Release, $old_build)"
if [ -d "$old_src" ]; then
  git -C "$old_src" checkout -q --detach "$rev"
else
  git -C "$root" worktree add -q --detach "$old_src" "$rev"
fi
cmake -S "$old_src" -B "$old_build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$old_build" --target tpf -j2 >/dev/null

# The built tool (bin/tpf, or src/cli/tpf in older trees), not an installed copy of it.
built_tpf() { find "$1" -name tpf -type f -perm -u+x -not -path "*/prefix/*" | head -1; }
new_tpf=$(built_tpf "$root/build/release")
old_tpf=$(built_tpf "$old_build")
robot="$root/data/arm4.robot.json"
log="$work/log.csv"
echo "compare: simulating ${seconds} s of log"
"$new_tpf" simulate --scenario "$root/data/scenarios/excitation-undeclared.json" --seed 3 \
  --duration "$seconds" --out "$log" >/dev/null

# Wall and CPU (user + system) seconds of identify + diagnose with one tpf binary: one
# `tpf diagnose --identify-out` (both from one reading of the log, as the tool offers them).
run_tree() {
  local tpf=$1 out=$2
  /usr/bin/time -f "%e %U %S" -o "$work/t" "$tpf" diagnose --log "$log" --robot "$robot" \
    --identify-out "$work/$out.params.json" --json "$work/$out.diagnosis.json" \
    >"$work/$out.txt" 2>/dev/null
  awk '{printf "%.1f %.1f\n", $1, $2 + $3}' "$work/t"
}

printf '%-4s %-6s %9s %9s\n' rep tree wall_s cpu_s
for ((r = 1; r <= reps; ++r)); do
  for tree in old new; do
    tpf=$old_tpf
    [ "$tree" = new ] && tpf=$new_tpf
    read -r wall cpu < <(run_tree "$tpf" "$tree")
    printf '%-4s %-6s %9s %9s\n' "$r" "$tree" "$wall" "$cpu"
    echo "$tree $wall $cpu" >>"$work/all"
  done
done
median() { sort -n | awk '{a[NR] = $1} END {print NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
wo=$(awk '$1 == "old" {print $2}' "$work/all" | median)
wn=$(awk '$1 == "new" {print $2}' "$work/all" | median)
co=$(awk '$1 == "old" {print $3}' "$work/all" | median)
cn=$(awk '$1 == "new" {print $3}' "$work/all" | median)
awk -v wo="$wo" -v wn="$wn" -v co="$co" -v cn="$cn" 'BEGIN {
  printf "median  old %.1f s wall %.1f s CPU · new %.1f s wall %.1f s CPU · new/old %.3f wall, %.3f CPU\n",
    wo, co, wn, cn, wn / wo, cn / co }'
for tree in old new; do
  echo "--- $tree tree: tpf diagnose --identify-out"
  cat "$work/$tree.txt"
done
