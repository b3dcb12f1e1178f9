#!/usr/bin/env bash
# The figures of docs/dtg-vib.md, "The model's input and smoother": the demo
# and each built-in campaign run fitted with the defaults (input and smoother
# chosen), then `dtg-vib allan` before/after on the whole record, read by
# scripts/never-worse.py; and each model's choice (every candidate's mean
# validation rms and worst ADEV ratio on the validation rows).
#   scripts/never-worse.sh [target/release] [/tmp/never-worse]
set -eu
BIN=$(cd "${1:-target/release}" && pwd); W=${2:-/tmp/never-worse}
HERE=$(cd "$(dirname "$0")" && pwd)
rm -rf "$W"; mkdir -p "$W"; cd "$W"
"$BIN/dtg-vib" demo --out demo --quiet > /dev/null
"$BIN/dtg-vib" allan --data demo/simulation/record.csv --model demo/final/model.json --json --quiet > allan-demo.json
files=(allan-demo.json)
for s in x-axis y-axis z-axis triaxial_hidden; do
  "$BIN/dtg-vib" simulate --builtin $s --out sim-$s --quiet > /dev/null
  "$BIN/dtg-vib" fit --data sim-$s/record.csv --calib sim-$s/calibration.json --out $s.json --quiet > fit-$s.txt
  "$BIN/dtg-vib" allan --data sim-$s/record.csv --model $s.json --json --quiet > allan-$s.json
  files+=(allan-$s.json)
done
python3 "$HERE/never-worse.py" "${files[@]}"
for s in x-axis y-axis z-axis triaxial_hidden; do echo "== fit $s"; sed -n '/^input and smoother/,/against raw/p' fit-$s.txt; done
