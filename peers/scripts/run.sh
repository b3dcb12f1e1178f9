#!/usr/bin/env bash
# Peer comparison of the rbf library (through the `rbf` CLI, which times the fit
# in-process as `fit_seconds`) with numpy / scikit-learn / scipy, on the same data file.
#
#   peers/scripts/run.sh peer    # OLS, k-means, all points vs the Python peers (default)
#   peers/scripts/run.sh large   # fit time and peak memory against N, M = 5000 candidates
#   peers/scripts/run.sh allan   # `dtg-vib allan` against allantools.oadev on the demo's record
#
# Environment: PYTHON (a Python with peers/scripts/requirements.txt; default: a virtual
# environment with those pins, made once in target/peer-venv and remade when they change),
# REPS (repetitions per side, default 5), OUT (work directory, default /tmp/rbf-peer),
# THREADS (the thread counts our side runs with, default "<cores> 1"), PY_THREADS
# (the OpenBLAS and OpenMP thread counts the Python side runs with, default THREADS:
# each side at each count, compared count for count),
# CARGO_TARGET_DIR (default ./target). The sides alternate repetition by repetition
# so that a noisy neighbour on a shared machine hits both alike; medians are quoted.
#
# Load: the load average is printed before and after, and the CPU time other processes
# took during the runs (the machine's busy time less this script's) as cores. Ratios
# measured on a loaded machine say little (docs/performance.md, "Contention"): when the
# load average before the runs, or the other processes' cores during them, exceed
# MAX_LOAD (default 1.5), `peer` prints the load and where the raw runs are, not the
# ratios, and exits with status 3, unless ALLOW_LOADED=1 (then the table is headed
# "MEASURED UNDER LOAD").
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
pins=$here/requirements.txt
if [[ -n ${PYTHON:-} ]]; then
    PY=$PYTHON
else
    venv=$root/target/peer-venv
    if ! cmp -s "$pins" "$venv/requirements.txt" 2>/dev/null; then
        echo "run.sh: making $venv from $pins" >&2
        rm -rf "$venv"
        python3 -m venv "$venv"
        "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$pins"
        cp "$pins" "$venv/requirements.txt"
    fi
    PY=$venv/bin/python
fi
REPS=${REPS:-5}
OUT=${OUT:-/tmp/rbf-peer}
NCPU=$(getconf _NPROCESSORS_ONLN) # not nproc: it follows OMP_NUM_THREADS
THREADS=${THREADS:-"$NCPU 1"}
PY_THREADS=${PY_THREADS:-$THREADS}
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
        "Python $("$PY" -c 'import sys, numpy, scipy; print(sys.version.split()[0], "numpy", numpy.__version__, "scipy", scipy.__version__)');" \
        "our threads: $THREADS; Python threads: $PY_THREADS"
}

json_field() { "$PY" -c "import json,sys; print(json.loads(sys.stdin.readline())['$1'])"; }

MAX_LOAD=${MAX_LOAD:-1.5}
loadavg() { cut -d' ' -f1-3 /proc/loadavg; }
# Busy and total jiffies of all cores (/proc/stat: user nice system idle iowait irq
# softirq steal), and this script's children's CPU seconds (bash's `times`).
busy_jiffies() { awk '/^cpu / {print $2 + $3 + $4 + $7 + $8 + $9}' /proc/stat; }
# `times` runs in this shell (a pipe or $(...) would fork and see no children).
own_seconds() {
    times >"$OUT/.times"
    tail -1 "$OUT/.times" | awk '{split($1, u, "m"); split($2, s, "m"); print u[1] * 60 + u[2] + s[1] * 60 + s[2]}'
}
load_start() {
    LOAD_BEFORE=$(loadavg)
    BUSY_BEFORE=$(busy_jiffies)
    own_seconds >"$OUT/.own"
    OWN_BEFORE=$(cat "$OUT/.own")
    WALL_BEFORE=$(date +%s.%N)
    echo "load average before: $LOAD_BEFORE"
}
# Sets LOAD_OK=1 when the machine was quiet enough for ratios, else 0, and prints why.
load_end() {
    local hz busy own wall
    hz=$(getconf CLK_TCK)
    busy=$(busy_jiffies)
    own_seconds >"$OUT/.own"
    own=$(cat "$OUT/.own")
    wall=$(date +%s.%N)
    LOAD_AFTER=$(loadavg)
    OTHERS=$(awk -v b0="$BUSY_BEFORE" -v b1="$busy" -v hz="$hz" -v o0="$OWN_BEFORE" -v o1="$own" \
        -v w0="$WALL_BEFORE" -v w1="$wall" \
        'BEGIN {v = ((b1 - b0) / hz - (o1 - o0)) / (w1 - w0); if (v < 0) v = 0; printf "%.2f", v}')
    echo "load average after: $LOAD_AFTER (it includes these runs);" \
        "other processes used $OTHERS cores on average during the runs"
    LOAD_OK=$(awk -v l="${LOAD_BEFORE%% *}" -v o="$OTHERS" -v m="$MAX_LOAD" \
        'BEGIN {print (l <= m && o <= m) ? 1 : 0}')
}

peer() {
    local data=$OUT/windows_2500.csv
    local beta
    beta=$("$PY" "$here/peer.py" gen --train 2500 --val 2500 --out "$data" | json_field beta)
    machine
    load_start
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
        for pt in $PY_THREADS; do
            OPENBLAS_NUM_THREADS=$pt OMP_NUM_THREADS=$pt "$PY" "$here/peer.py" run --data "$data" \
                --beta "$beta" --k 100 --smoothing 1e-8 --threads "$pt" \
                --methods "${METHODS:-cgs,cgs_cdist,ols,kmeans,rbfi}" >>"$OUT/python.jsonl"
        done
    done
    for t in $THREADS; do
        RBF_THREADS=$t "$BOUND" "$data" "$beta" >>"$OUT/rust.jsonl"
    done
    for pt in $PY_THREADS; do
        OPENBLAS_NUM_THREADS=$pt OMP_NUM_THREADS=$pt "$PY" "$here/peer.py" run --data "$data" \
            --beta "$beta" --methods matvec --threads "$pt" >>"$OUT/python.jsonl"
    done
    load_end
    if [[ $LOAD_OK != 1 ]]; then
        if [[ ${ALLOW_LOADED:-0} != 1 ]]; then
            echo "not reporting ratios: load above $MAX_LOAD (before: ${LOAD_BEFORE%% *}," \
                "other processes: $OTHERS cores); the runs are in $OUT/rust.jsonl and" \
                "$OUT/python.jsonl; ALLOW_LOADED=1 reports them anyway" >&2
            exit 3
        fi
        echo "MEASURED UNDER LOAD (before: ${LOAD_BEFORE%% *}, other processes: $OTHERS cores):" \
            "the ratios below are not those of a quiet machine"
    fi
    "$PY" "$here/peer.py" report "$OUT/rust.jsonl" "$OUT/python.jsonl"
}

large() {
    machine
    load_start
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
    load_end
    [[ $LOAD_OK == 1 ]] || echo "MEASURED UNDER LOAD: these times are not those of a quiet machine"
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
