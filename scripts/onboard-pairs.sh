#!/usr/bin/env bash
# Issue 37 §4: one onboard step of this checkout against a baseline
# commit's, Rust evaluator and exported C f64, in the same run, with the
# physical floor beside each figure.
#
#   scripts/onboard-pairs.sh [--baseline REV] [--pairs N] [--work DIR] [--count]
#
# The models are the step bench's (crates/dtg-vib/benches/onboard_step.rs,
# seeded tables, K = 100 centres per channel): the paper's six channels per
# channel on the statistics input (the issue's first figure), on the raw
# 50-sample window, and with one centre set; the nine rate gyros of three
# IMUs, each gyro's network on its own IMU's accelerometers (the issue's
# second), and on the first IMU's. The baseline runs each model in the
# layout it wrote (2 for the paper's unit, 3 for another); layout 3 has one
# list of window signals for every gyro, so its side of "own IMU" is the
# same-size model on the first IMU's (nine inputs per network either way).
#
# Per model, N alternating pairs of four runs (baseline Rust, current Rust,
# baseline C, current C), each the median ns per step of 1001 batches of
# 100 steps (scripts/onboard-pairs/harness.{rs,c}); printed: both sides'
# medians of those, the ratios, the load before and after, the checksums
# of both sides (equal tables, equal inputs: they agree), and the floor:
# the step's flops and exponentials (dtg_onboard::Model::flops_per_step,
# exps_per_step) over the peak scripts/onboard-pairs/peak.c measures on the
# instruction set the kernels run (AVX2 where the CPU has it: both sides
# choose it at run time; else SSE2; -march=native printed beside).
# --count: instructions per step under valgrind --tool=callgrind instead
# (load-proof; (Ir of 2000 steps − Ir of 1000) / 1000).
# Defaults: --baseline 5b6a72d, --pairs 5, --work target/onboard-pairs; the
# baseline is built in target/bench-pairs/baseline-SHA (bench-pairs.sh's).
# A figure taken at load > 1.5 decides nothing: the script says so beside it.
# $CC and $ONBOARD_CFLAGS (default -O2 -std=c99) build both sides' C; with
# ONBOARD_CFLAGS="-O2 -std=c99 -DDTG_NO_CLONES" the current side's portable build.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
REV=5b6a72d; PAIRS=5; WORK="$ROOT/target/onboard-pairs"; COUNT=0
while [ $# -gt 0 ]; do
    case "$1" in
        --baseline) REV=$2; shift 2 ;;
        --pairs) PAIRS=$2; shift 2 ;;
        --work) WORK=$2; shift 2 ;;
        --count) COUNT=1; shift ;;
        -h|--help) sed -n '2,33p' "$0"; exit 0 ;;
        *) echo "onboard-pairs: unknown argument '$1' (flags: --baseline REV, --pairs N, --work DIR, --count)" >&2; exit 2 ;;
    esac
done
mkdir -p "$WORK"; WORK=$(cd "$WORK" && pwd)
HERE="$ROOT/scripts/onboard-pairs"
CC=${CC:-cc}; COPTS=${ONBOARD_CFLAGS:-"-O2 -std=c99"}

# The baseline in its own worktree and target folder; the harness and the
# C exporter of its tables as examples of its crates.
SHA=$(git -C "$ROOT" rev-parse --short "$REV^{commit}")
BASE="$ROOT/target/bench-pairs/baseline-$SHA"
[ -d "$BASE/src" ] || git -C "$ROOT" worktree add --detach "$BASE/src" "$SHA" >/dev/null
mkdir -p "$BASE/src/crates/dtg-onboard/examples/onboard_harness"
cp "$HERE/harness.rs" "$BASE/src/crates/dtg-onboard/examples/onboard_harness/main.rs"
cp "$HERE/inputs.rs" "$BASE/src/crates/dtg-onboard/examples/onboard_harness/"
cp "$HERE/baseline_c.rs" "$BASE/src/crates/dtg-vib/examples/onboard_baseline_c.rs"
(cd "$BASE/src" && cargo build --release --target-dir "$BASE/target" \
    -p dtg-onboard --example onboard_harness >&2 \
    && cargo build --release --target-dir "$BASE/target" -p dtg-vib --example onboard_baseline_c >&2)
OLD_RS="$BASE/target/release/examples/onboard_harness"

# This checkout: its harness, and the bench's tables (both layouts), costs and C.
(cd "$ROOT" && cargo build --release -p dtg-onboard --example onboard_harness >&2)
NEW_RS="$ROOT/target/release/examples/onboard_harness"
T="$WORK/tables"; rm -rf "$T"; mkdir -p "$T"
(cd "$ROOT" && ONBOARD_TABLES_DIR="$T" ONBOARD_TABLES_ONLY=1 cargo bench -p dtg-vib --bench onboard_step >&2)

# name | the baseline's tables | unit file its C needs (none: the paper's)
THREE="$ROOT/crates/dtg-vib/tests/fixtures/onboard/three-imus.toml"
MODELS="rust_step_k100_stats3x3_smoothed|rust_step_k100_stats3x3_smoothed.then|
rust_step_nine_gyros_k100_stats_own_imu|rust_step_nine_gyros_k100_stats_first_imu.then|$THREE
rust_step_k100_w50x3|rust_step_k100_w50x3.then|
rust_step_k100_stats3x3_smoothed_shared|rust_step_k100_stats3x3_smoothed_shared.then|
rust_step_nine_gyros_k100_stats_first_imu|rust_step_nine_gyros_k100_stats_first_imu.then|$THREE"

# Each side's C with the harness.
while IFS='|' read -r name then unit; do
    "$BASE/target/release/examples/onboard_baseline_c" "$T/$then.dtgo" "$T/$name-c-old" $unit
    for side in "$name-c-old" "$name-c"; do
        (cd "$T/$side" && $CC $COPTS -I. dtg_model.c "$HERE/harness.c" -lm -o harness)
    done
done <<< "$MODELS"

load() { cut -d' ' -f1 /proc/loadavg; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.3f", a/b}'; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); baseline $SHA, current $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet || echo '+changes'); $CC $COPTS"

if [ "$COUNT" = 1 ]; then
    # Instructions of one step: the difference of two step counts cancels
    # the start (parsing, the warm-up).
    ir() {
        local out="$WORK/cg.out" a b
        valgrind --tool=callgrind --callgrind-out-file="$out" "$@" 1000 >/dev/null 2>&1
        a=$(awk '/^summary:/{print $2}' "$out")
        valgrind --tool=callgrind --callgrind-out-file="$out" "$@" 2000 >/dev/null 2>&1
        b=$(awk '/^summary:/{print $2}' "$out")
        echo $(( (b - a) / 1000 ))
    }
    printf "%-42s %12s %12s %6s %12s %12s %6s\n" model "Rust then" "Rust now" ratio "C then" "C now" ratio
    while IFS='|' read -r name then unit; do
        ro=$(ir "$OLD_RS" "$T/$then.dtgo"); rn=$(ir "$NEW_RS" "$T/$name.dtgo")
        co=$(ir "$T/$name-c-old/harness"); cn=$(ir "$T/$name-c/harness")
        printf "%-42s %12s %12s %6s %12s %12s %6s   instructions per step\n" \
            "$name" "$ro" "$rn" "$(ratio "$rn" "$ro")" "$co" "$cn" "$(ratio "$cn" "$co")"
    done <<< "$MODELS"
    exit 0
fi

# The machine's peak on the instruction set the step's kernels run: both
# sides choose AVX2 at run time where the CPU has it (dtg-onboard's vector.rs,
# the C's target_clones), so peak.c built with -mavx2 (no FMA: the kernels
# round as SSE2 does), else x86-64's SSE2 (-O3 without -march, so that gcc
# vectorises peak.c's loops as it does the step's at -O2; also with
# -DDTG_NO_CLONES). Both peaks, and -march=native's, are printed.
PEAK_C="$T/rust_step_k100_stats3x3_smoothed-c"
$CC -O3 -std=c99 -I"$PEAK_C" "$HERE/peak.c" -lm -o "$WORK/peak"
$CC -O3 -mavx2 -std=c99 -I"$PEAK_C" "$HERE/peak.c" -lm -o "$WORK/peak-avx2"
$CC -O3 -march=native -std=c99 -I"$PEAK_C" "$HERE/peak.c" -lm -o "$WORK/peak-native"
read -r SF SE < <("$WORK/peak" 2>/dev/null)
read -r AF AE < <("$WORK/peak-avx2" 2>/dev/null)
read -r NF NE < <("$WORK/peak-native" 2>/dev/null)
if grep -qw avx2 /proc/cpuinfo && [[ "$COPTS" != *DTG_NO_CLONES* ]]; then
    GF=$AF; GE=$AE; ISA="AVX2, the kernels' clone"
else
    GF=$SF; GE=$SE; ISA="x86-64 baseline (SSE2)"
fi
echo "peak (-O3 -std=c99): $SF flops/ns, $SE exponentials/ns; -mavx2: $AF, $AE; -march=native: $NF, $NE; the floor at $ISA"

printf "%-42s %9s %9s %6s %9s %9s %6s %9s %7s  %s\n" model "Rust then" "Rust now" ratio "C then" "C now" ratio "floor" "flops" "exps  load"
while IFS='|' read -r name then unit; do
    l0=$(load); : > "$WORK/times"
    for i in $(seq "$PAIRS"); do
        echo "$("$OLD_RS" "$T/$then.dtgo") $("$NEW_RS" "$T/$name.dtgo") $("$T/$name-c-old/harness") $("$T/$name-c/harness")" >> "$WORK/times"
    done
    l1=$(load)
    # Columns: old Rust ns, sum; new Rust ns, sum; old C ns, sum; new C ns, sum.
    ro=$(cut -d' ' -f1 "$WORK/times" | median); rn=$(cut -d' ' -f3 "$WORK/times" | median)
    co=$(cut -d' ' -f5 "$WORK/times" | median); cn=$(cut -d' ' -f7 "$WORK/times" | median)
    read -r flops exps < "$T/$name.cost"
    floor=$(awk -v f="$flops" -v e="$exps" -v pf="$GF" -v pe="$GE" 'BEGIN{printf "%.1f", f/pf + e/pe}')
    verdict=""; awk -v a="$l0" -v b="$l1" 'BEGIN{exit !(a>1.5||b>1.5)}' && verdict="  (load > 1.5: decides nothing)"
    printf "%-42s %9s %9s %6s %9s %9s %6s %9s %7s %5s  %s -> %s%s\n" "$name" "$ro" "$rn" "$(ratio "$rn" "$ro")" \
        "$co" "$cn" "$(ratio "$cn" "$co")" "$floor" "$flops" "$exps" "$l0" "$l1" "$verdict"
    sums=$(head -1 "$WORK/times" | awk '{print $2, $4, $6, $8}')
    echo "  ns per step of every run (Rust then, now, C then, now): $(awk '{printf "%s/%s/%s/%s ", $1, $3, $5, $7}' "$WORK/times")"
    # Each harness sums its first gyro's compensated rate (Rust over the
    # warm-up, C over every step): then and now agree within 1e-9.
    echo "  checksums (Rust then, now, C then, now): $sums$(echo "$sums" | awk 'function d(a, b) {return (a-b)^2 > 1e-18*(a^2+1)} {if (d($1,$2) || d($3,$4)) print "  THEN AND NOW DIFFER"}')"
done <<< "$MODELS"
echo "floor: flops / peak flops + exponentials / peak exponentials, ns per step, on the kernels' instruction set ($ISA)"
