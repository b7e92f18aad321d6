#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""vtkMesoSelectAtoms against MDAnalysis' select_atoms on the same files, in the same run: every
expression must select the same atoms (matched by serial number in PDB files, by position in
GRO files). Each row pairs a MesoLens expression with the MDAnalysis one that means the same:
`within D of X` is `(around D X) or X` there, `x < 5` is `prop x < 5`, `chain A` is
`chainID A`, MDAnalysis 2.4 has no `water`, `lipid` or `hydrogen` keywords, and its `and` and
`or` have the same precedence (left to right) and `around` takes all that follows, so its side
has parentheses where MesoLens (like VMD) needs none. Distances are plain
(periodic=False), as in MesoLens. Skips (77) without ../shared/data or MDAnalysis."""
import os
import sys
import unittest
import warnings

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import mesolens
from mesolens import array_names

SHARED = os.environ.get("MESOLENS_SHARED_DATA_DIR", "")
try:
    import MDAnalysis
except ImportError:
    MDAnalysis = None

WATER = "resname HOH WAT SOL TIP3 SPC"

# Expressions for every protein file: (MesoLens, MDAnalysis).
PROTEIN_EXPRESSIONS = [
    ("name CA", "name CA"),
    ("name C*", "name C*"),
    ("name N CA C O", "name N CA C O"),
    ("name [NO]*", "name [NO]*"),
    ("resname ALA GLY", "resname ALA GLY"),
    ("resname G*", "resname G*"),
    ("resid 10-20", "resid 10-20"),
    ("resid 10:20", "resid 10:20"),
    ("resid 3 7 12-14", "resid 3 7 12-14"),
    ("resnum 5-9", "resnum 5-9"),
    ("index 0-99", "index 0-99"),
    ("index 17", "index 17"),
    ("bynum 1-100", "bynum 1-100"),
    ("id 10-20", "id 10-20"),
    ("protein", "protein"),
    ("backbone", "backbone"),
    ("not protein", "not protein"),
    ("protein and not backbone", "protein and not backbone"),
    ("element C", "element C"),
    ("element N O S", "element N O S"),
    ("not element C", "not element C"),
    ("water", WATER),
    ("not water and not protein", "not (%s) and not protein" % WATER),
    ("chain A", "chainID A"),
    ("(name CA or name CB) and resid 1-30", "(name CA or name CB) and resid 1-30"),
    ("name CA and not (resid 1-5 or resid 20-30)", "name CA and not (resid 1-5 or resid 20-30)"),
    ("resname PRO and name N CA C O", "resname PRO and name N CA C O"),
    ("within 5 of resid 10", "(around 5 resid 10) or resid 10"),
    ("exwithin 5 of resid 10", "around 5 resid 10"),
    ("around 8 (resid 1 and name CA)", "around 8 (resid 1 and name CA)"),
    ("within 3.5 of water", "(around 3.5 (%s)) or (%s)" % (WATER, WATER)),
    ("same residue as within 4 of resid 10", "same residue as ((around 4 resid 10) or resid 10)"),
    ("byres name SG", "byres name SG"),
    ("same residue as exwithin 2.5 of name SG", "byres (around 2.5 name SG)"),
    ("x < 10", "prop x < 10"),
    ("z >= 5 and y < 20", "prop z >= 5 and prop y < 20"),
    ("beta > 20", "prop tempfactor > 20"),
    ("occupancy < 1", "prop occupancy < 1"),
    ("protein and x > 15 or water and z < 10",
     "(protein and prop x > 15) or ((%s) and prop z < 10)" % WATER),
    ("not name H*", "not name H*"),
]

# (file, extra expressions that only make sense there)
PROTEIN_FILES = [
    ("1crn.pdb", []),
    ("1ubq.pdb", []),
    ("1aki.pdb", []),
    ("3o5r.pdb", [("altloc A", "altloc A"), ("altloc B and name CA", "altloc B and name CA")]),
    ("1l2y.pdb", [("hydrogen", "element H"), ("protein and not hydrogen", "protein and not element H")]),
    ("1bna.pdb", [("nucleic", "nucleic"), ("name P", "name P"),
                  ("nucleic and name O5' C5'", "nucleic and name O5' C5'"),
                  ("within 6 of name P", "(around 6 name P) or name P")]),
]

MEMBRANE_EXPRESSIONS = {
    "yiip_popepopg.gro": [
        ("lipid", "resname POPE POPG"),
        ("lipid and name P", "resname POPE POPG and name P"),
        ("protein", "protein"),
        ("backbone", "backbone"),
        ("same residue as (name P and z > 60)", "byres (name P and prop z > 60)"),
        ("lipid and within 6 of protein", "resname POPE POPG and (around 6 protein)"),
        ("resname ZNM", "resname ZNM"),
        ("not lipid and not protein", "not resname POPE POPG and not protein"),
        ("resid 100-120 and name CA", "resid 100-120 and name CA"),
    ],
    "martini_dppc_chol_bilayer.gro": [
        ("lipid", "resname DPPC CHOL"),
        ("name PO4", "name PO4"),
        ("resname CHOL and name ROH", "resname CHOL and name ROH"),
        ("same residue as (name PO4 and z > 40)", "byres (name PO4 and prop z > 40)"),
        ("within 8 of resname CHOL", "(around 8 resname CHOL) or resname CHOL"),
        ("name C* and not name C1*", "name C* and not name C1*"),
    ],
    "dppc128_slipids_323K.gro": [
        ("lipid", "resname DPPC"),
        ("name P N", "name P N"),
        ("water", "resname SOL"),
        ("water and within 5 of name P", "resname SOL and ((around 5 name P) or name P)"),
    ],
}


def ours(path, expression):
    """MesoLens: the selected atoms and each atom's serial number."""
    if path.endswith(".gro"):
        reader = mesolens.vtkMesoTrajectoryReader()
        reader.SetTopologyFileName(path)
        reader.MakeMoleculesWholeOff()  # the file's coordinates, as MDAnalysis reads them
    else:
        reader = mesolens.vtkMesoStructureReader()
        reader.SetFileName(path)
        reader.KeepAllAlternateLocationsOn()
    select = mesolens.vtkMesoSelectAtoms()
    select.SetInputConnection(reader.GetOutputPort())
    select.SetSelection(expression)
    select.Update()
    out = select.GetOutput()
    mask = vtk_to_numpy(out.GetPointData().GetArray("Selected")).astype(bool)
    serials = vtk_to_numpy(out.GetPointData().GetArray(array_names.SerialNumber))
    return mask, serials


def theirs(universe, expression):
    mask = np.zeros(len(universe.atoms), dtype=bool)
    mask[universe.select_atoms(expression, periodic=False).indices] = True
    return mask


class SelectionsAgreeWithMDAnalysis(unittest.TestCase):
    def compare(self, path, pairs):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            universe = MDAnalysis.Universe(path)
        checked = 0
        for mine, reference in pairs:
            with self.subTest(file=os.path.basename(path), expression=mine):
                mask, serials = ours(path, mine)
                expected = theirs(universe, reference)
                self.assertEqual(len(mask), len(expected))
                if not path.endswith(".gro"):
                    # Same atoms in the same order: the serial numbers agree one to one.
                    np.testing.assert_array_equal(serials, universe.atoms.ids)
                differing = np.flatnonzero(mask != expected)
                self.assertEqual(len(differing), 0,
                                 "%d atoms differ (first: %s); MesoLens selects %d, MDAnalysis %d"
                                 % (len(differing), differing[:5], mask.sum(), expected.sum()))
                checked += 1
        return checked

    def test_proteins(self):
        for name, extra in PROTEIN_FILES:
            self.compare(os.path.join(SHARED, "proteins", name), PROTEIN_EXPRESSIONS + extra)

    def test_membranes(self):
        for name, pairs in MEMBRANE_EXPRESSIONS.items():
            self.compare(os.path.join(SHARED, "membranes", name), pairs)

    def test_enough_expressions(self):
        distinct = {mine for mine, _ in PROTEIN_EXPRESSIONS}
        distinct |= {mine for _, extra in PROTEIN_FILES for mine, _ in extra}
        distinct |= {mine for pairs in MEMBRANE_EXPRESSIONS.values() for mine, _ in pairs}
        self.assertGreaterEqual(len(distinct), 40)


if __name__ == "__main__":
    if MDAnalysis is None or not os.path.isdir(os.path.join(SHARED, "proteins")):
        print("skipped: needs python3-mdanalysis and ../shared/data")
        sys.exit(77)
    unittest.main()
