# Copyright (c) 2026 The Surface_mesh_correspondence developers.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The batch runner's throughput: 8 FAUST_r pairs (pairs 1, 38, 75, ... of test_pairs.txt) through
`python3 -m comap.batch` with 1 and with 2 dask workers (one thread each), against `comap match`
alone on the same pairs (one thread), and the accuracy the batch reports.

    PYTHONPATH=build/python python3 benchmark/bench_batch.py [--data ../shared/data] [--comap build/bin/comap]
        [--pairs 8] [--out /tmp/bench_batch]

Prints one line per run: wall time, seconds per pair, pairs per minute; then the throughput ratio
of 2 workers over 1 and the batch's overhead per pair over `comap match` (wall time per pair of
the 1-worker batch minus comap's, both on one thread; the batch also evaluates each pair).
"""

import argparse
import csv
import os
import shutil
import subprocess
import sys
import time


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    parser.add_argument("--comap", default=os.path.join(here, "..", "build", "bin", "comap"))
    parser.add_argument("--pairs", type=int, default=8)
    parser.add_argument("--out", default="/tmp/bench_batch")
    args = parser.parse_args()
    faust = os.path.abspath(os.path.join(args.data, "FAUST_r"))
    with open(os.path.join(faust, "test_pairs.txt")) as f:
        lines = [l.split() for l in f if l.strip()]
    pairs = [lines[k] for k in range(0, len(lines), 37)][: args.pairs]
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    pairs_csv = os.path.join(args.out, "pairs.csv")
    with open(pairs_csv, "w") as f:
        f.write("source,target,gt_source,gt_target\n")
        for a, b in pairs:
            f.write(f"{faust}/off/{a}.off,{faust}/off/{b}.off,{faust}/corres/{a}.vts,{faust}/corres/{b}.vts\n")
    print(f"{len(pairs)} FAUST_r pairs: " + ", ".join(f"{a}-{b}" for a, b in pairs))

    def report(label, seconds):
        print(f"{label:<34} {seconds:7.1f} s   {seconds / len(pairs):6.2f} s/pair   "
              f"{60 * len(pairs) / seconds:5.2f} pairs/min", flush=True)
        return seconds

    start = time.perf_counter()
    for k, (a, b) in enumerate(pairs):
        subprocess.run([args.comap, "match", f"{faust}/off/{a}.off", f"{faust}/off/{b}.off", "--out-12",
                        os.path.join(args.out, f"comap_{k}_12.map"), "--out-21", os.path.join(args.out, f"comap_{k}_21.map"),
                        "--threads", "1", "--quiet"], check=True, stdout=subprocess.DEVNULL)
    comap_seconds = report("comap match, 1 thread, one by one", time.perf_counter() - start)

    results = {}
    for workers in (1, 2):
        out = os.path.join(args.out, f"workers_{workers}")
        start = time.perf_counter()
        run = subprocess.run([sys.executable, "-m", "comap.batch", pairs_csv, "--out", out, "--workers", str(workers),
                              "--quiet"], capture_output=True, text=True)
        seconds = time.perf_counter() - start
        if run.returncode != 0:
            sys.exit(f"the batch with {workers} worker(s) failed: {run.stderr}")
        results[workers] = report(f"comap.batch, {workers} worker(s) x 1 thread", seconds)
        with open(os.path.join(out, "results.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    errors = [float(r[k]) for r in rows for k in ("mean_error_12", "mean_error_21")]
    within = [float(r[k]) for r in rows for k in ("within_0.025_12", "within_0.025_21")]
    print(f"throughput ratio, 2 workers / 1: {results[1] / results[2]:.2f}x")
    print(f"overhead per pair, 1-worker batch over comap match: {(results[1] - comap_seconds) / len(pairs):+.2f} s")
    print(f"accuracy (results.csv): mean geodesic error {sum(errors) / len(errors):.4f}, "
          f"within 0.025 {100 * sum(within) / len(within):.1f}% ({len(errors)} maps)")


if __name__ == "__main__":
    main()
