#!/usr/bin/env python3
"""Turns bench/solve_bench's JSON output into the cost-curve table (CSV, seconds per
evaluation against n) that `chasles plot --log` draws as docs/images/cost-curves.png:

  build/bench/solve_bench --benchmark_filter='^(Free|Chain|Pile)[A-Za-z]*/' \\
      --benchmark_out=solve.json --benchmark_out_format=json
  scripts/cost_curves.py solve.json docs/images/cost-curves.csv  (several JSON files: the
      later ones' runs replace the earlier ones')
  build/bin/chasles plot docs/images/cost-curves.csv n free chain_sparse chain_dense \\
      pile_sticking_sparse pile_sticking_dense pile_sliding_sparse pile_sliding_dense \\
      --log -o docs/images/cost-curves.png

With --select, the mode-selection benchmarks instead (CPU time per SelectContactModes, the
figure of docs/benchmarks.md, "Sparse mode selection"):

  build/bench/solve_bench --benchmark_filter='^Select' \\
      --benchmark_out=select.json --benchmark_out_format=json
  scripts/cost_curves.py --select select.json docs/images/mode-selection-costs.csv
  build/bin/chasles plot docs/images/mode-selection-costs.csv n resting_sparse resting_dense \\
      sideways_sparse sideways_dense chain_sparse chain_dense lengthwise_sparse \\
      lengthwise_dense --log -o docs/images/mode-selection-costs.png

Where a benchmark was repeated, the median of its repetitions is taken. A size a benchmark
did not time (the dense ones stop at n = 300) is written as 0, which the
log-log plot leaves out."""

import json
import sys

SERIES = {
    "FreeBodies": "free",
    "ChainSparse": "chain_sparse",
    "ChainDense": "chain_dense",
    "PileStickingSparse": "pile_sticking_sparse",
    "PileStickingDense": "pile_sticking_dense",
    "PileSlidingSparse": "pile_sliding_sparse",
    "PileSlidingDense": "pile_sliding_dense",
}
SELECT_SERIES = {
    "SelectRestingSparse": "resting_sparse",
    "SelectRestingDense": "resting_dense",
    "SelectSidewaysSparse": "sideways_sparse",
    "SelectSidewaysDense": "sideways_dense",
    "SelectChainSparse": "chain_sparse",
    "SelectChainDense": "chain_dense",
    "SelectLengthwiseSparse": "lengthwise_sparse",
    "SelectLengthwiseDense": "lengthwise_dense",
}
SCALE = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def main(sources, dst, series=SERIES, clock="real_time"):
    runs = []
    for src in sources:  # a later file's run of the same benchmark replaces an earlier one
        with open(src) as f:
            runs += json.load(f)["benchmarks"]
    times = {}
    for r in runs:
        # A single run, or the median of repetitions (--benchmark_repetitions).
        median = r.get("run_type") == "aggregate" and r.get("aggregate_name") == "median"
        if (r.get("run_type") != "iteration" and not median) or "/" not in r["name"]:
            continue
        name, n = r.get("run_name", r["name"]).split("/")[:2]
        if name in series:
            times[(series[name], int(n))] = r[clock] * SCALE[r["time_unit"]]
    sizes = sorted({n for (_, n) in times})
    with open(dst, "w") as f:
        f.write(",".join(["n"] + [f"{c} [s]" for c in series.values()]) + "\n")
        for n in sizes:
            row = [str(n)] + [repr(times.get((c, n), 0.0)) for c in series.values()]
            f.write(",".join(row) + "\n")


if __name__ == "__main__":
    args = sys.argv[1:]
    select = args[:1] == ["--select"]
    if select:
        args = args[1:]
    if len(args) < 2:
        sys.exit("usage: cost_curves.py [--select] BENCH.json [BENCH.json...] OUT.csv")
    if select:
        main(args[:-1], args[-1], SELECT_SERIES, "cpu_time")
    else:
        main(args[:-1], args[-1])
