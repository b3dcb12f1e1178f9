#!/usr/bin/env python3
"""The Python overhead of ``model.compensate(record)`` on the demo record
(issue 36 §3: under 10 % of the Rust time).

``model.compensate`` is one call into the extension, which times itself from
entry to exit (the record staged as the file the command reads, read with the
unit, compensated, the output read back as columns): that is the Rust time.
The Python overhead is the rest of the call: the DataFrame's columns handed over
as float64 arrays and the result made a DataFrame. For scale, the command
``dtg-vib compensate`` on the same files is timed too (a process: start-up and
the output file included). REPS calls each, alternating; medians. The load
changes the figures: measure on a quiet machine and give the load average
(printed). `--quick` runs 3 repetitions, to check the script runs.

    python python/bench/compensate_overhead.py --dtg-vib target/release/dtg-vib
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import rbf_dtg
from rbf_dtg import _native
from rbf_dtg.loop import _frame, _source


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dtg-vib", type=Path, default=None, help="the command, to time it too")
    p.add_argument("--reps", type=int, default=30)
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
    reps = 3 if a.quick else a.reps

    record, calibration, _ = rbf_dtg.simulate(builtin="demo")
    model = rbf_dtg.fit(record, calibration=calibration)
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        record.to_csv(d / "record.csv", index=False)
        model.save(d / "model.json")
        total, rust, cli = [], [], []
        for _ in range(reps):
            start = time.perf_counter()
            table, _, inside = model._native.compensate(_source(record))
            frame = _frame(table)
            total.append(time.perf_counter() - start)
            rust.append(inside)
            if a.dtg_vib:
                start = time.perf_counter()
                subprocess.run([str(a.dtg_vib), "compensate", "--model", str(d / "model.json"),
                                "--data", str(d / "record.csv"), "--out", str(d / "comp.csv"), "--quiet"],
                               check=True, capture_output=True)
                cli.append(time.perf_counter() - start)
                os.remove(d / "comp.csv")
        # the same as the public call, which also turns notes into warnings
        assert frame.equals(model.compensate(record))

    median = statistics.median
    overhead = [t - r for t, r in zip(total, rust)]
    print(f"demo record: {len(record)} rows x {record.shape[1]} columns; {reps} calls; load average {os.getloadavg()}")
    print(f"model.compensate: median {1e3 * median(total):.2f} ms, of which Rust {1e3 * median(rust):.2f} ms")
    print(f"Python overhead: median {1e3 * median(overhead):.3f} ms = "
          f"{100 * median(o / r for o, r in zip(overhead, rust)):.2f} % of the Rust time (required < 10 %)")
    if cli:
        print(f"dtg-vib compensate (a process, writing its CSV): median {1e3 * median(cli):.2f} ms")


if __name__ == "__main__":
    main()
