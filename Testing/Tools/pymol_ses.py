#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""PyMOL's solvent-excluded surface of a structure file, headless: its area and enclosed volume
from PyMOL's own triangles, and the time PyMOL takes to build it (loading and export excluded).
The benchmark of vtkMesoMolecularSurface runs it as its PyMOL baseline.

    pymol_ses.py FILE [--quality 1] [--probe 1.4]

Prints `area=<Å2> volume=<Å3> seconds=<s> triangles=<n>` and exits 0, or exits 2 when the file
does not load or the surface is empty. HETATM records are removed (EDTSurf reads ATOM records
only), every alternate location is kept (as EDTSurf does).
"""
import argparse
import os
import sys
import time

import numpy as np


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("file")
    parser.add_argument("--quality", type=int, default=1, help="surface_quality")
    parser.add_argument("--probe", type=float, default=1.4, help="solvent_radius, Å")
    args = parser.parse_args()

    import pymol
    from pymol import cmd
    pymol.finish_launching(["pymol", "-cq"])

    def leave(code):
        # Once PyMOL runs, sys.exit's status is lost.
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)

    try:
        cmd.load(args.file, "m")
    except Exception as error:  # PyMOL raises its own CmdException
        print(f"load failed: {error}", file=sys.stderr)
        leave(2)
    if "m" not in cmd.get_names("objects") or cmd.count_atoms("m") == 0:
        print("no atoms loaded", file=sys.stderr)
        leave(2)
    cmd.remove("hetatm")
    cmd.flag("ignore", "all", "clear")  # PyMOL's surfaces skip atoms flagged at load
    cmd.set("surface_quality", args.quality)
    cmd.set("solvent_radius", args.probe)
    cmd.set("surface_type", 0)
    cmd.hide("everything")
    cmd.show("surface", "m")
    start = time.perf_counter()
    cmd.draw()  # headless, this builds the surface and nothing else
    seconds = time.perf_counter() - start

    _, obj = cmd.get_mtl_obj()  # the triangles, in camera space (a rigid motion)
    positions, normals, faces = [], [], []
    for line in obj.splitlines():
        if line.startswith("v "):
            positions.append(line[2:])
        elif line.startswith("vn "):
            normals.append(line[3:])
        elif line.startswith("f "):
            faces.append(line[2:].replace("//", " "))
    if not faces:
        print("empty surface", file=sys.stderr)
        leave(2)
    positions = np.array(" ".join(positions).split(), float).reshape(-1, 3)
    normals = np.array(" ".join(normals).split(), float).reshape(-1, 3)
    faces = np.array(" ".join(faces).split(), np.int64).reshape(-1, 6) - 1
    corners, corner_normals = faces[:, 0::2], faces[:, 1::2]
    a, b, c = (positions[corners[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(cross, axis=1).sum()
    # Each triangle oriented by its vertex normals (PyMOL's winding agrees; a guard).
    sign = np.where(np.einsum("ij,ij->i", cross, normals[corner_normals].sum(1)) < 0, -1.0, 1.0)
    volume = (sign * np.einsum("ij,ij->i", a, np.cross(b, c))).sum() / 6.0
    print(f"area={area:.3f} volume={volume:.3f} seconds={seconds:.4f} triangles={len(faces)}")
    leave(0)


if __name__ == "__main__":
    main()
