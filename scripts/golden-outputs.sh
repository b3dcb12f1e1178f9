#!/usr/bin/env bash
# Runs a fixed set of dtg-vib and rbf commands with the binaries in $1 and
# collects every output (stdout, stderr, files) under $2, so that two builds
# can be compared with: diff -r A B  (the work dir is always /tmp/golden-work,
# so paths printed are the same; report dates are masked).
set -u
# Used to check that a refactor changes no output: build, run it on the old
# and the new binaries, diff -r the two DEST folders.
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=$(cd "$1" && pwd); DEST=$(mkdir -p "$2" && cd "$2" && pwd)
W=${GOLDEN_WORK:-/tmp/golden-work}; rm -rf "$W"; mkdir -p "$W"; cd "$W"
d() { "$BIN/dtg-vib" "$@"; }
r() { "$BIN/rbf" "$@"; }
run() { local name=$1; shift; "$@" > "$name.out" 2> "$name.err"; echo "exit $?" >> "$name.out"; }
run demo d demo --out demo --quiet
for s in triaxial_hidden x-axis y-axis z-axis flight; do run sim-$s d simulate --builtin $s --out sim-$s --quiet; done
C=sim-z-axis/calibration.json
TH=sim-triaxial_hidden
run fit-th d fit --data $TH/record.csv --calib $TH/calibration.json --out th.json --json --quiet
run fit-th-text d fit --data $TH/record.csv --calib $TH/calibration.json --out th2.json --quiet
run diag-th d diagnose --model th.json --data $TH/record.csv --json --quiet
run diag-th-text d diagnose --model th.json --data $TH/record.csv --report diag-th-report --quiet
run explain-th d explain --data $TH/record.csv --calib $TH/calibration.json --out th-final.json --json --quiet
run explain-th-text d explain --data $TH/record.csv --calib $TH/calibration.json --out th-final2.json --quiet
run report-th d report --model th-final.json --baseline th.json --data $TH/record.csv --out report-th --quiet
run comp-th d compensate --model th.json --data $TH/record.csv --out comp-th.csv --quiet
run res-th d residues --model th.json --data $TH/record.csv --out res-th.csv --quiet
run allan-demo d allan --data demo/simulation/record.csv --model demo/final/model.json --json --quiet
run allan-demo-text d allan --data demo/simulation/record.csv --model demo/final/model.json --report allan-report --quiet
run fit-z d fit --data sim-z-axis/record.csv --calib $C --out z.json --json --quiet
run check-zx d check --model z.json --data sim-x-axis/record.csv --json --quiet
run check-zx-text d check --model z.json --data sim-x-axis/record.csv --report check-report --quiet
run check-zf d check --model z.json --data sim-flight/record.csv --quiet
run fit-xyz d fit --data sim-x-axis/record.csv --data sim-y-axis/record.csv --data sim-z-axis/record.csv --calib $C --out xyz.json --json --quiet
run diag-xyz d diagnose --model xyz.json --data sim-x-axis/record.csv --data sim-y-axis/record.csv --data sim-z-axis/record.csv --json --quiet
run fit-causal d fit --causal --data $TH/record.csv --calib $TH/calibration.json --out causal.json --quiet
run export-c d export --model causal.json --lang c --out exp-c --quiet
run export-text d export --model causal.json --lang text --quiet
# the same loop on units other than the paper's (and the paper by name)
for u in tetra triad dual-triad; do run demo-$u d demo --unit $u --out demo-$u --quiet; done
run sim-tetra d simulate --unit tetra --builtin triaxial_hidden --duration 60 --out sim-tetra --quiet
T=sim-tetra
run fit-tetra d fit --data $T/record.csv --calib $T/calibration.json --unit tetra --out tetra.json --json --quiet
run fit-tetra-text d fit --data $T/record.csv --calib $T/calibration.json --unit tetra --out tetra2.json --quiet
run diag-tetra d diagnose --model tetra.json --data $T/record.csv --json --quiet
run explain-tetra d explain --data $T/record.csv --calib $T/calibration.json --unit tetra --out tetra-final.json --json --quiet
run check-tetra d check --model tetra-final.json --data $T/record.csv --json --quiet
run check-tetra-text d check --model tetra-final.json --data $T/record.csv --quiet
run comp-tetra d compensate --model tetra.json --data $T/record.csv --out comp-tetra.csv --quiet
run res-tetra d residues --model tetra.json --data $T/record.csv --out res-tetra.csv --json --quiet
run allan-tetra d allan --data $T/record.csv --model tetra-final.json --json --quiet
run report-tetra d report --model tetra-final.json --baseline tetra.json --data $T/record.csv --out report-tetra --quiet
run fit-tetra-causal d fit --causal --data $T/record.csv --calib $T/calibration.json --unit tetra --out tetra-causal.json --quiet
run export-tetra-c d export --model tetra-causal.json --lang c --out exp-tetra-c --quiet
run export-tetra-text d export --model tetra-causal.json --lang text --quiet
run fit-th-paper d fit --data $TH/record.csv --calib $TH/calibration.json --unit paper --out th-paper.json --json --quiet
run rbf-fit r fit --data $ROOT/peers/data/sunspots/sunspots_lags9.csv --target y --max-centers 20 --out rbf.json --json
run rbf-cv r cv --data $ROOT/peers/data/sunspots/sunspots_lags9.csv --target y --split blocked --folds 4 --sizes 5,10,20
run rbf-predict r predict --model rbf.json --data $ROOT/peers/data/sunspots/sunspots_lags9.csv --out pred.csv --json
# mask report dates and the binary's path
grep -rl 'date (UTC)' . | xargs -r sed -i 's/[0-9]\{4\}-[0-9][0-9]-[0-9][0-9] [0-9:]\{8\} UTC/DATE/g'
grep -rl "$BIN" . | xargs -r sed -i "s#$BIN#BIN#g"; grep -rl "$W" . | xargs -r sed -i "s#$W#WORK#g"
# mask timings
sed -i -E 's/(seconds[a-z_]*)":[0-9.e+-]+/\1":T/g; s/"(kernel_matrix|selection|weights|widths)":[0-9.e+-]+/"\1":T/g; s/\([0-9.]+ (s|ms)\)/(T)/g; s/; [0-9.]+ s$/; T s/' *.out *.err
rm -rf "$DEST"; mkdir -p "$(dirname "$DEST")"; cp -r "$W" "$DEST"
