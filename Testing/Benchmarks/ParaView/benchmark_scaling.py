#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The scaling benchmark: the membrane mapping of k x k tiles and a rendered frame of the mapped
membrane (MesoLens Atoms in ParaView's render view, composited by IceT) on 1 and 2 MPI ranks of
this machine, time and peak memory per rank, and the 2-rank / 1-rank ratios measured in the same
run. One rank uses every core's thread; each of 2 ranks gets its share (VTK_SMP_MAX_THREADS).

    benchmark_scaling.py PVBATCH MPIRUN PLUGIN DATA_DIR [--smoke]   (default 15 x 15 tiles)
"""
import os
import glob
import re
import subprocess
import sys
import tempfile

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scaling_scene.py")


def run(launcher, scene, threads):
    """Each rank's results {rank: {key: value}} of one run of the scene."""
    environment = dict(os.environ)
    environment["VTK_SMP_MAX_THREADS"] = str(threads)
    with tempfile.TemporaryDirectory() as output:
        command = [*launcher, *scene, output]
        done = subprocess.run(command, env=environment, capture_output=True, text=True,
                              timeout=1500)
        if done.returncode != 0:
            sys.stderr.write(done.stdout[-4000:] + done.stderr[-4000:])
            raise SystemExit(f"the run failed: {' '.join(command)}")
        results = {}
        for path in glob.glob(os.path.join(output, "rank*.txt")):
            rank = int(re.search(r"rank(\d+)", os.path.basename(path)).group(1))
            with open(path, encoding="utf-8") as stream:
                results[rank] = {key: float(value) for key, value in
                                 (line.split() for line in stream if line.strip())}
        return results


def main():
    if len(sys.argv) < 5:
        raise SystemExit(__doc__)
    pvbatch, mpirun, plugin, data = sys.argv[1:5]
    tiles = 3 if "--smoke" in sys.argv else 15
    cores = os.cpu_count() or 1
    scene = [SCENE, plugin, data, str(tiles)]
    one = run([pvbatch], scene, cores)
    two = run([mpirun, "--allow-run-as-root", "--oversubscribe", "-np", "2", pvbatch], scene,
              max(1, cores // 2))
    atoms = int(sum(r["end_atoms"] for r in one.values()))
    print(f"input: DPPC patch (dppc128_slipids_323K.gro, waters removed, 16,640 atoms) in "
          f"{tiles} x {tiles} tiles = {atoms:,} atoms on mito5_outer_membrane.obj, polynomial "
          f"mapping, MesoLens Atoms at 1024 x 768; {cores} cores")
    check = int(sum(r["end_atoms"] for r in two.values()))
    if check != atoms:
        raise SystemExit(f"2 ranks mapped {check} atoms, 1 rank {atoms}")
    for key, label in (("mapping_s", "mapping"), ("first_frame_s", "first frame"),
                       ("next_frame_s", "next frame")):
        a, b = one[0][key], two[0][key]
        print(f"{label}: 1 rank {a:.3f} s, 2 ranks {b:.3f} s, ratio 2/1 {b / a:.2f}")
    shares = ", ".join(f"rank {r}: {int(two[r]['end_atoms']):,}" for r in sorted(two))
    print(f"atoms per rank on 2 ranks: {shares}")
    print(f"start: ParaView and the mesh, {one[0]['start_peak_mib']:.0f} MiB per rank")
    for stage, label in (("mapped", "after the mapping"), ("end", "after two frames")):
        peak_one = one[0][f"{stage}_peak_mib"] - one[0]["start_peak_mib"]
        peaks_two = [two[r][f"{stage}_peak_mib"] - two[r]["start_peak_mib"] for r in sorted(two)]
        print(f"peak memory per rank above the start, {label}: 1 rank {peak_one:.0f} MiB; "
              f"2 ranks " + ", ".join(f"{p:.0f}" for p in peaks_two) +
              f" MiB; ratio largest 2-rank / 1-rank {max(peaks_two) / peak_one:.2f}")


if __name__ == "__main__":
    main()
