#!/usr/bin/env bash
# Peer comparison of the rbf library (through the `rbf` CLI, which times the fit
# in-process as `fit_seconds`) with numpy / scikit-learn / scipy, on the same data file.
#
#   peers/scripts/run.sh peer    # OLS, k-means, all points vs the Python peers (default)
#   peers/scripts/run.sh large   # fit time and peak memory against N, M = 5000 candidates
#   peers/scripts/run.sh allan   # `dtg-vib allan` against allantools.oadev on the demo's record
#
# Environment: PYTHON (a Python with peers/scripts/requirements.txt; default python3),
# REPS (repetitions per side, default 5), OUT (work directory, default /tmp/rbf-peer),
# THREADS (the thread counts our side runs with, default "<cores> 1"), PY_THREADS
# (if set, OpenBLAS and OpenMP threads of the Python side),
# CARGO_TARGET_DIR (default ./target). The sides alternate repetition by repetition
# so that a noisy neighbour on a shared machine hits both alike; medians are quoted.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
PY=${PYTHON:-python3}
REPS=${REPS:-5}
OUT=${OUT:-/tmp/rbf-peer}
NCPU=$(getconf _NPROCESSORS_ONLN) # not nproc: it follows OMP_NUM_THREADS
THREADS=${THREADS:-"$NCPU 1"}
if [[ -n ${PY_THREADS:-} ]]; then
    export OPENBLAS_NUM_THREADS=$PY_THREADS OMP_NUM_THREADS=$PY_THREADS
fi
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
mode=${1:-peer}
mkdir -p "$OUT"

if [[ $mode != allan ]]; then
    (cd "$root" && cargo build --quiet --release -p rbf-cli --bin rbf --example stream_bound)
fi
RBF=$CARGO_TARGET_DIR/release/rbf
BOUND=$CARGO_TARGET_DIR/release/examples/stream_bound

machine() {
    echo "machine: $NCPU cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
        "$(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); $(date -u '+%Y-%m-%d %H:%M UTC');" \
        "rbf $(git -C "$root" rev-parse --short HEAD); load $(cut -d' ' -f1-3 /proc/loadavg);" \
        "our threads: $THREADS; Python threads: ${PY_THREADS:-default ($NCPU)}"
}

json_field() { "$PY" -c "import json,sys; print(json.loads(sys.stdin.readline())['$1'])"; }

peer() {
    local data=$OUT/windows_2500.csv
    local beta
    beta=$("$PY" "$here/peer.py" gen --train 2500 --val 2500 --out "$data" | json_field beta)
    machine
    echo "data: $data (2500 training + 2500 validation windows of 50 samples), Gaussian β = $beta"
    : >"$OUT/rust.jsonl"
    : >"$OUT/python.jsonl"
    local common=(--data "$data" --target y --split-column split --width "$beta" --json --quiet
        --out "$OUT/model.json")
    for rep in $(seq "$REPS"); do
        echo "repetition $rep/$REPS" >&2
        for t in $THREADS; do
            "$RBF" fit --threads "$t" "${common[@]}" --centers ols --max-centers 100 >>"$OUT/rust.jsonl"
            "$RBF" fit --threads "$t" "${common[@]}" --centers kmeans --max-centers 100 >>"$OUT/rust.jsonl"
            "$RBF" fit --threads "$t" "${common[@]}" --centers all --ridge 1e-8 >>"$OUT/rust.jsonl"
        done
        "$PY" "$here/peer.py" run --data "$data" --beta "$beta" --k 100 --smoothing 1e-8 \
            --methods cgs,ols,kmeans,rbfi >>"$OUT/python.jsonl"
    done
    for t in $THREADS; do
        RBF_THREADS=$t "$BOUND" "$data" "$beta" >>"$OUT/rust.jsonl"
    done
    "$PY" "$here/peer.py" run --data "$data" --beta "$beta" --methods matvec >>"$OUT/python.jsonl"
    "$PY" "$here/peer.py" report "$OUT/rust.jsonl" "$OUT/python.jsonl"
}

large() {
    machine
    echo "| N | candidates M | K | threads | fit (s) | kernel matrix (s) | per pick (ms) | peak RSS (MiB) | val NMSE |"
    echo "|---|---|---|---|---|---|---|---|---|"
    for n in ${SIZES:-1000 2000 5000 10000 20000 50000}; do
        local data=$OUT/windows_$n.csv
        local beta
        beta=$("$PY" "$here/peer.py" gen --train "$n" --val 1000 --out "$data" | json_field beta)
        for t in $THREADS; do
            /usr/bin/time -v -o "$OUT/time_$n.txt" "$RBF" fit --threads "$t" --data "$data" \
                --target y --split-column split --centers ols --candidates 5000 \
                --max-centers 100 --width "$beta" --json --quiet --out "$OUT/model_$n.json" \
                >"$OUT/large_$n.json"
            local rss
            rss=$(awk -F: '/Maximum resident set size/ {printf "%.0f", $2/1024}' "$OUT/time_$n.txt")
            "$PY" - "$OUT/large_$n.json" "$rss" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
m = min(r["n_train"], r["candidates"])
km = r["stage_seconds"].get("kernel_matrix", float("nan"))
print(f"| {r['n_train']} | {m} | {r['n_centers']} | {r['threads']} | {r['fit_seconds']:.2f} | {km:.2f} | "
      f"{r['seconds_per_pick'] * 1e3:.1f} | {sys.argv[2]} | {r['val_nmse']:.4f} |")
EOF
        done
    done
}

allan() {
    (cd "$root" && cargo build --quiet --release -p dtg-vib --bin dtg-vib)
    local bin=$CARGO_TARGET_DIR/release/dtg-vib
    rm -rf "$OUT/demo"
    "$bin" demo --out "$OUT/demo" --quiet >/dev/null
    "$PY" "$here/allan.py" compare --bin "$bin" --data "$OUT/demo/simulation/record.csv" \
        --model "$OUT/demo/final/model.json"
}

case $mode in
    peer) peer ;;
    large) large ;;
    allan) allan ;;
    *) echo "usage: $0 [peer|large|allan]" >&2; exit 2 ;;
esac
