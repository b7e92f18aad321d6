#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Prints the reference numbers that the reader tests hard-code, computed with independent tools
(Debian's python3-gemmi and python3-mdanalysis), so they can be re-derived and audited:

    apt-get install python3-gemmi python3-mdanalysis
    /usr/bin/python3 Testing/Tools/reference_values.py

Counts follow MesoLens' documented conventions: alternate locations resolved to one conformer
(gemmi's remove_alternative_conformations), molecules = one per residue except that the polymer
residues of one chain form one molecule, bonds = MDAnalysis' distance guess with covalent radii
+ 0.45 Å inside each molecule, united with the file's CONECT records.
"""
import os
import sys
import warnings

import gemmi
import numpy as np

warnings.filterwarnings("ignore")
import MDAnalysis as mda  # noqa: E402
from MDAnalysis.topology.guessers import guess_bonds  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data")


def structure_counts(path):
    try:
        st = gemmi.read_structure(path)
    except RuntimeError:
        # Pre-remediation files keep an id and serial in columns 73-80: drop columns 77-80.
        lines = [ln[:76] if ln.startswith(("ATOM", "HETATM")) else ln
                 for ln in open(path).read().splitlines()]
        st = gemmi.read_pdb_string("\n".join(lines))
    models = len(st)
    all_atoms = sum(1 for _ in st[0].all())
    st.remove_alternative_conformations()
    model = st[0]
    atoms = sum(1 for _ in model.all())
    residues = sum(len(ch) for ch in model)
    chains = len({ch.name for ch in model})
    hydrogens = sum(1 for cra in model.all() if cra.atom.is_hydrogen())
    spans = set()
    for h in st.helices:
        spans.add((h.start.chain_name, str(h.start.res_id.seqid), str(h.end.res_id.seqid)))
    for sheet in st.sheets:
        for s in sheet.strands:
            spans.add((s.start.chain_name, str(s.start.res_id.seqid), str(s.end.res_id.seqid)))
    return dict(models=models, atoms_all_altlocs=all_atoms, atoms=atoms, residues=residues,
                chains=chains, hydrogens=hydrogens, ss_spans=len(spans))


def polymer(resname):
    info = gemmi.find_tabulated_residue(resname)
    return info is not None and (info.is_amino_acid() or info.is_nucleic_acid())


def bond_count(path, coarse_grained=False):
    u = mda.Universe(path)
    conect = set()
    if hasattr(u, "bonds"):
        conect = {tuple(sorted((b[0].index, b[1].index))) for b in u.bonds}
    # One molecule per residue, except the polymer residues of one (non-blank) chain.
    molecule = []
    key_of = {}
    for atom in u.atoms:
        chain = getattr(atom, "chainID", "") if hasattr(atom, "chainID") else ""
        res = atom.residue
        if polymer(res.resname) and chain.strip():
            key = ("polymer", chain)
        else:
            key = ("residue", res.ix)
        molecule.append(key_of.setdefault(key, len(key_of)))
    molecule = np.array(molecule)
    guessed = set()
    if coarse_grained:
        radii = {t: 2.5 for t in set(u.atoms.types)}
    else:
        if hasattr(u.atoms, "elements"):
            u.atoms.types = u.atoms.elements  # guess_bonds looks radii up by type
        radii = {t: gemmi.Element(t if t.strip() else "X").covalent_r + 0.225
                 for t in set(u.atoms.types)}
    for m in np.unique(molecule):
        idx = np.where(molecule == m)[0]
        if len(idx) < 2:
            continue
        # guess_bonds returns global atom indices.
        for a, b in guess_bonds(u.atoms[idx], u.atoms[idx].positions, vdwradii=radii,
                                fudge_factor=1.0, lower_bound=0.4):
            guessed.add(tuple(sorted((int(a), int(b)))))
    return len(guessed | conect), len(conect)


def main():
    for name in ["1crn.pdb", "1crn.cif", "1ubq.pdb", "1ubq.cif", "1l2y.pdb", "1aki.pdb",
                 "1hpv.pdb", "4we2.pdb", "1dix.pdb", "1dix.cif", "3o5r.pdb", "3o5r.cif",
                 "1bna.pdb", "4gxy.pdb", "1tii.pdb", "1d3z.pdb"]:
        print(name, structure_counts(os.path.join(DATA, "proteins", name)))
    for name in ["1crn.pdb", "1ubq.pdb", "1aki.pdb", "1bna.pdb", "4gxy.pdb", "1tii.pdb"]:
        print(name, "bonds (total, conect):", bond_count(os.path.join(DATA, "proteins", name)))
    for name in ["martini_dppc_chol_bilayer.gro", "dppc128_slipids_323K.gro"]:
        u = mda.Universe(os.path.join(DATA, "membranes", name))
        print(name, "atoms", len(u.atoms), "residues", len(u.residues))
    u = mda.Universe(os.path.join(DATA, "membranes", "yiip_popepopg.gro"),
                     os.path.join(DATA, "membranes", "yiip_popepopg.xtc"))
    print("yiip frames", len(u.trajectory), "atoms", len(u.atoms), "residues", len(u.residues))
    for frame in (0, 2, 4):
        ts = u.trajectory[frame]
        print("yiip frame", frame, "time", ts.time, "box", ts.dimensions.tolist())
        for i in (0, 1000, 43479):
            print("   atom", i, u.atoms[i].position.tolist())
    u = mda.Universe(os.path.join(DATA, "membranes", "martini_dppc_vesicle.gro"),
                     os.path.join(DATA, "membranes", "martini_dppc_vesicle.xtc"))
    print("vesicle frames", len(u.trajectory), "atoms", len(u.atoms))
    for frame in (7, 10):
        ts = u.trajectory[frame]
        print("vesicle frame", frame, "time", ts.time, "box", ts.dimensions.tolist())
        for i in (0, 20000, 36863):
            print("   atom", i, u.atoms[i].position.tolist())


if __name__ == "__main__":
    sys.exit(main())
