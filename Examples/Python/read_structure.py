#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Read a PDB or mmCIF file with MesoLens and summarise it; optionally save the atoms as VTP.

    read_structure.py [FILE] [--output atoms.vtp]
"""
import argparse
import collections
import os

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

import mesolens
from mesolens import array_names

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
KINDS = {0: "coil", 1: "alpha helix", 2: "3-10 helix", 3: "pi helix", 4: "strand", 8: "other helix"}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("file", nargs="?", default=os.path.join(DATA, "proteins", "1tii.pdb"))
    parser.add_argument("--output", help="write the atoms and bonds to this .vtp file")
    args = parser.parse_args()

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(args.file)
    if not reader.GetExecutive().Update():
        raise SystemExit(f"cannot read {args.file}")
    atoms = reader.GetOutput()
    data = atoms.GetPointData()
    chains = data.GetAbstractArray(array_names.ChainId)
    elements = data.GetAbstractArray(array_names.Element)
    structure = vtk_to_numpy(data.GetArray(array_names.SecondaryStructure))
    print(f"{args.file}: {reader.GetNumberOfModels()} model(s), {atoms.GetNumberOfPoints()} atoms, "
          f"{atoms.GetNumberOfLines()} bonds, "
          f"{int(vtk_to_numpy(data.GetArray(array_names.MoleculeId)).max()) + 1} molecules")
    per_chain = collections.Counter(chains.GetValue(i) for i in range(chains.GetNumberOfValues()))
    print("atoms per chain:", dict(sorted(per_chain.items())))
    per_element = collections.Counter(elements.GetValue(i) for i in range(elements.GetNumberOfValues()))
    print("atoms per element:", dict(per_element.most_common(6)))
    for kind, count in sorted(collections.Counter(structure.tolist()).items()):
        print(f"  {KINDS.get(kind, kind)}: {count} atoms")
    if args.output:
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(args.output)
        writer.SetInputData(atoms)
        writer.Write()
        print("wrote", args.output)


if __name__ == "__main__":
    main()
