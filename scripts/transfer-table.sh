#!/usr/bin/env bash
# The transfer table of docs/campaign.md §6: the campaign's built-in runs
# simulated, the four models fitted (z run; x, y, z runs; the same with
# §4's added terms; the three runs with the paper's az window), each checked on
# every run and on the flight with `check --json`, and the table printed
# from those files by scripts/transfer-table.py.
#   scripts/transfer-table.sh [target/release] [/tmp/transfer-table]
set -eu
BIN=$(cd "${1:-target/release}" && pwd); W=${2:-/tmp/transfer-table}
HERE=$(cd "$(dirname "$0")" && pwd)
rm -rf "$W"; mkdir -p "$W"; cd "$W"
for run in x-axis y-axis z-axis flight; do "$BIN/dtg-vib" simulate --builtin $run --out $run --quiet > /dev/null; done
"$BIN/dtg-vib" fit --data z-axis/record.csv --calib z-axis/calibration.json --out z.json --quiet > /dev/null
"$BIN/dtg-vib" fit --data x-axis/record.csv --data y-axis/record.csv --data z-axis/record.csv \
    --calib z-axis/calibration.json --out xyz.json --quiet > /dev/null
"$BIN/dtg-vib" fit --data x-axis/record.csv --data y-axis/record.csv --data z-axis/record.csv \
    --calib z-axis/calibration.json --add-effect X=gg_SS --add-effect X1=gg_SS \
    --add-effect Y=gg_OO --add-effect Y1=gg_II --out xyz-effects.json --quiet > /dev/null
# The three runs' model with the paper's window, az alone (the default
# before --window-signals auto, which takes ax,ay,az on these runs).
"$BIN/dtg-vib" fit --data x-axis/record.csv --data y-axis/record.csv --data z-axis/record.csv \
    --calib z-axis/calibration.json --window-signals az --out xyz-az.json --quiet > /dev/null
for m in z xyz xyz-effects xyz-az; do for r in x-axis y-axis z-axis flight; do
    "$BIN/dtg-vib" check --model $m.json --data $r/record.csv --json --quiet > check-$m-$r.json 2> /dev/null
done; done
python3 "$HERE/transfer-table.py" .
