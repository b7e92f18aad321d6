#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The MDAnalysis baseline of BenchmarkAtomSelection: reads a .gro file, then for each
expression (one per line on stdin) prints "count median_ms" of select_atoms(periodic=False),
the median of `repeats` runs after one warm-up run.

    mdanalysis_select.py FILE.gro REPEATS < expressions.txt
"""
import statistics
import sys
import time
import warnings

import MDAnalysis


def main():
    path, repeats = sys.argv[1], int(sys.argv[2])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        universe = MDAnalysis.Universe(path)
    for line in sys.stdin:
        expression = line.strip()
        if not expression:
            continue
        count = len(universe.select_atoms(expression, periodic=False))
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            universe.select_atoms(expression, periodic=False)
            times.append(time.perf_counter() - start)
        print(count, 1000.0 * statistics.median(times), flush=True)


if __name__ == "__main__":
    main()
