#!/usr/bin/env bash
# Same-run speed comparison of this checkout's dtg-vib against a baseline
# commit's (issue 37): builds the baseline into its own folder, prepares each
# goal's inputs once, then runs baseline and current alternately, N pairs,
# and prints per goal both medians (wall s, peak RSS MiB), the ratio, and the
# load average before and after, with the machine (nproc, CPU model).
#
#   scripts/bench-pairs.sh [--baseline REV] [--pairs N] [--work DIR] GOAL...
#
# GOAL: demo       `dtg-vib demo --quiet` (5 pairs is the issue's count)
#       fit1m      the 1,000,000-row fit of docs/performance.md (its record is
#                  made once, ~200 MB; 3 pairs is enough: each run is ~15 s)
#       explain3   `explain` over the three campaign runs (docs/campaign.md)
# Defaults: --baseline 5b6a72d, --pairs 5, --work target/bench-pairs.
# A figure taken at load > 1.5 decides nothing: the script says so beside it.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
REV=5b6a72d; PAIRS=5; WORK="$ROOT/target/bench-pairs"; GOALS=()
while [ $# -gt 0 ]; do
    case "$1" in
        --baseline) REV=$2; shift 2 ;;
        --pairs) PAIRS=$2; shift 2 ;;
        --work) WORK=$2; shift 2 ;;
        -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
        demo|fit1m|explain3) GOALS+=("$1"); shift ;;
        *) echo "bench-pairs: unknown argument '$1' (goals: demo, fit1m, explain3; flags: --baseline REV, --pairs N, --work DIR)" >&2; exit 2 ;;
    esac
done
[ ${#GOALS[@]} -gt 0 ] || { echo "bench-pairs: name at least one goal: demo, fit1m, explain3" >&2; exit 2; }
mkdir -p "$WORK"; WORK=$(cd "$WORK" && pwd)

# The baseline in its own worktree and target folder, built once per commit.
SHA=$(git -C "$ROOT" rev-parse --short "$REV^{commit}")
BASE="$WORK/baseline-$SHA"
if [ ! -x "$BASE/target/release/dtg-vib" ]; then
    [ -d "$BASE/src" ] || git -C "$ROOT" worktree add --detach "$BASE/src" "$SHA" >/dev/null
    (cd "$BASE/src" && cargo build --release -p dtg-vib --target-dir "$BASE/target" >&2)
fi
(cd "$ROOT" && cargo build --release -p dtg-vib >&2)
OLD="$BASE/target/release/dtg-vib"; NEW="$ROOT/target/release/dtg-vib"

load() { cut -d' ' -f1 /proc/loadavg; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); baseline $SHA, current $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet || echo '+changes')"

# Runs "$@" with BIN set to $1's binary, in a fresh folder; prints "wall rss_mib".
timed() {
    local bin=$1 dir=$2; shift 2
    rm -rf "$dir"; mkdir -p "$dir"
    ( cd "$dir" && BIN=$bin /usr/bin/time -f '%e %M' -o "$dir/.time" bash -c "$*" >/dev/null 2>"$dir/.stderr" ) \
        || { echo "bench-pairs: a run failed in $dir (see $dir/.stderr)" >&2; exit 1; }
    awk '{printf "%s %.0f\n", $1, $2/1024}' "$dir/.time"
}

# One goal: its command (with $BIN), PAIRS alternating pairs, the table row.
pairs() {
    local goal=$1 cmd=$2 l0 l1 o n
    l0=$(load); : > "$WORK/$goal.old"; : > "$WORK/$goal.new"
    for i in $(seq "$PAIRS"); do
        timed "$OLD" "$WORK/run-old" "$cmd" >> "$WORK/$goal.old"
        timed "$NEW" "$WORK/run-new" "$cmd" >> "$WORK/$goal.new"
    done
    l1=$(load)
    o=$(cut -d' ' -f1 "$WORK/$goal.old" | median); n=$(cut -d' ' -f1 "$WORK/$goal.new" | median)
    local om nm; om=$(cut -d' ' -f2 "$WORK/$goal.old" | median); nm=$(cut -d' ' -f2 "$WORK/$goal.new" | median)
    local verdict=""; awk -v a="$l0" -v b="$l1" 'BEGIN{exit !(a>1.5||b>1.5)}' && verdict="  (load > 1.5: decides nothing)"
    printf "%-9s baseline %8.3f s %6s MiB  current %8.3f s %6s MiB  ratio %.3f  load %s -> %s%s\n" \
        "$goal" "$o" "$om" "$n" "$nm" "$(awk -v a="$n" -v b="$o" 'BEGIN{print a/b}')" "$l0" "$l1" "$verdict"
    echo "  all runs (wall s, peak MiB): baseline $(tr '\n' ' ' < "$WORK/$goal.old")| current $(tr '\n' ' ' < "$WORK/$goal.new")"
}

for g in "${GOALS[@]}"; do
    case "$g" in
        demo) pairs demo '"$BIN" demo --out d --quiet' ;;
        fit1m)
            if [ ! -f "$WORK/r1m.csv" ]; then
                for k in 0 1 2 3 4 5 6 7 8 9; do
                    "$NEW" simulate --builtin demo --seed $((100 + k)) --duration 2000 --out "$WORK/chunk$k" --quiet
                done
                python3 - "$WORK" <<'PY'
import sys
w = sys.argv[1]
with open(f"{w}/r1m.csv", "w") as out:
    for k in range(10):
        with open(f"{w}/chunk{k}/record.csv") as f:
            header = f.readline()
            if k == 0:
                out.write(header)
            for line in f:
                t, rest = line.split(",", 1)
                out.write(f"{float(t) + 2000.0 * k!r},{rest}")
PY
            fi
            pairs fit1m "\"\$BIN\" fit --data $WORK/r1m.csv --calib $WORK/chunk0/calibration.json --out m.json --quiet" ;;
        explain3)
            for s in x-axis y-axis z-axis; do
                [ -f "$WORK/$s/record.csv" ] || "$NEW" simulate --builtin "$s" --out "$WORK/$s" --quiet
            done
            pairs explain3 "\"\$BIN\" explain --data $WORK/x-axis/record.csv --data $WORK/y-axis/record.csv --data $WORK/z-axis/record.csv --calib $WORK/z-axis/calibration.json --out m.json --quiet" ;;
    esac
done
