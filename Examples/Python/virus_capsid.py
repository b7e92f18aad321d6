#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A whole virus capsid drawn from its asymmetric unit, with one protein picked out by a selection.

The phiX174 virion (1RB8: 5112 atoms in the file, 60 copies in its biological assembly, 306,720
atoms) or the PBCV-1 capsid (1M4X: 9693 atoms, 1680 copies, 16.3 million atoms), read with
vtkMesoStructureReader's Assembly "1" and ExpandAssembly off: the reader gives the asymmetric unit
(output 0) and the copies' matrices (output 1), and the impostor mapper draws the unit at every
copy in one instanced call, space-filling, with ambient occlusion. A vtkMesoSelectAtoms mask on
the unit colours the selection in every copy (by default the spike protein G of phiX174, chain A
of PBCV-1's three capsid-protein chains); everything else is grey.

    virus_capsid.py [--file ../shared/data/proteins/1rb8.pdb] [--assembly 1]
                    [--selection "chain G"] [--expanded] [--output capsid.png] [--size 600]

--expanded builds every copy's atoms on the CPU instead (as Mol* or PyMOL would), and draws
those: copy c > 0 of chain G is then named G-(c + 1), so the default selection becomes
"chain G G-*". Exits with 77 (skipped) when the file is absent.
"""
import argparse
import os
import sys
import time

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens
from mesolens.lens import write_png

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.environ.get("MESOLENS_SHARED_DATA_DIR",
                        os.path.join(HERE, "..", "..", "..", "shared", "data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", default=os.path.join(SHARED, "proteins", "1rb8.pdb"))
    parser.add_argument("--assembly", default="1")
    parser.add_argument("--selection", help='default "chain G" (1rb8) or "chain A" (others); '
                        'with --expanded, with the copies\' chains: "chain G G-*"')
    parser.add_argument("--expanded", action="store_true")
    parser.add_argument("--output", default="capsid.png")
    parser.add_argument("--size", type=int, default=600)
    args = parser.parse_args()
    if not os.path.exists(args.file):
        print("skipped: no", args.file)
        sys.exit(77)
    chain = "G" if "1rb8" in os.path.basename(args.file).lower() else "A"
    if args.selection is None:
        args.selection = "chain %s %s-*" % (chain, chain) if args.expanded else "chain " + chain

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(args.file)
    reader.SetAssembly(args.assembly)
    reader.SetExpandAssembly(args.expanded)
    select = mesolens.vtkMesoSelectAtoms()
    select.SetInputConnection(reader.GetOutputPort(0))
    select.SetSelection(args.selection)
    start = time.perf_counter()
    select.Update()
    atoms = select.GetOutput()
    if atoms.GetNumberOfPoints() == 0:
        sys.exit(1)
    chosen = atoms.GetPointData().GetArray("Selected")
    picked = sum(int(chosen.GetValue(i)) for i in range(chosen.GetNumberOfTuples()))
    copies = reader.GetOutput(1).GetNumberOfPoints()
    total = reader.GetAssemblyAtomCount(0)
    if args.expanded:
        print("%s assembly %s: %d copies, %d atoms built on the CPU (read, built and selected in "
              "%.2f s); '%s': %d atoms" % (os.path.basename(args.file), args.assembly, copies,
                                           atoms.GetNumberOfPoints(), time.perf_counter() - start,
                                           args.selection, picked))
    else:
        print("%s assembly %s: %d copies of %d atoms (%d atoms), drawn instanced (read and "
              "selected in %.2f s); '%s': %d atoms per copy (%d in all)"
              % (os.path.basename(args.file), args.assembly, copies, atoms.GetNumberOfPoints(),
                 total, time.perf_counter() - start, args.selection, picked, picked * copies))

    table = vtkLookupTable()
    table.SetNumberOfTableValues(2)
    table.SetTableValue(0, 0.78, 0.78, 0.8, 1.0)
    table.SetTableValue(1, 0.95, 0.55, 0.15, 1.0)
    table.SetTableRange(0, 1)
    mapper = mesolens.vtkMesoAtomMapper()
    mapper.SetInputConnection(select.GetOutputPort())
    if not args.expanded:
        mapper.SetAssemblyConnection(reader.GetOutputPort(1))
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Selected")
    mapper.ScalarVisibilityOn()
    mapper.SetLookupTable(table)
    mapper.SetScalarRange(0, 1)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.08, 0.09, 0.12)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.3)
    passes = mesolens.vtkMesoRenderPasses()
    passes.SSAOOn()
    passes.SetSSAORadius(12.0)                         # Å: capsids are 300 to 1900 Å across
    passes.SetSSAOBias(1.0)
    passes.SSAOBlurOn()
    passes.Apply(renderer)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    start = time.perf_counter()
    window.Render()
    print("first frame %.2f s" % (time.perf_counter() - start))
    write_png(window, args.output)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
