#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The MDAnalysis baseline of BenchmarkReaders' trajectories: reads a .gro topology and an .xtc
trajectory, then prints "frames frames_per_second": every frame read in order (coordinates as
MDAnalysis gives them, not made whole: its unwrap needs bonds, which a .gro file lacks), the
median of `repeats` passes after one warm-up pass.

    mdanalysis_trajectory.py FILE.gro FILE.xtc REPEATS
"""
import statistics
import sys
import time
import warnings

import MDAnalysis


def main():
    gro, xtc, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        universe = MDAnalysis.Universe(gro, xtc)
    frames = len(universe.trajectory)
    times = []
    for _ in range(repeats + 1):
        start = time.perf_counter()
        for timestep in universe.trajectory:
            timestep.positions.sum()  # touch the coordinates, as a reader's user would
        times.append(time.perf_counter() - start)
    print(frames, frames / statistics.median(times[1:]))


if __name__ == "__main__":
    main()
