#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws an assembly's ribbons, surface or atoms two ways, for the image tests: expanded (the
ribbons, surface or atoms of all the copies' atoms, vtkPolyDataMapper or vtkMesoAtomMapper) or
instanced (one copy's ribbons and surface, drawn at every copy by vtkGlyph3DMapper from the
structure reader's output 1, orientation AssemblyOrientation as quaternions; the asymmetric
unit's atoms drawn at every copy by vtkMesoAtomMapper with that output as its assembly input).
The assembly is crambin (Data/proteins/1crn.pdb) in a ring of three copies, 0, 120 and 240
degrees about z and 40 Å out, so that the copies do not touch (their surfaces are then the
surfaces of the copies). For the atoms, residues 24 on are chain B, and the second and third
copies take chain A alone: the instanced draw must hide chain B there.

    assembly_glyphs.py --mode expanded|instanced|wrong-orientation --what ribbons|surface|atoms
                       --output IMAGE [--size 240]

The ribbons and atoms of a rotated copy are the rotated ones: instanced and expanded pictures
agree pixel for pixel. A surface's lattice is not rotated with the copy, so its triangles differ
slightly: about 3 % of the pixels, at silhouettes (a wrong orientation: about 11 %).

wrong-orientation draws the instanced copies with each rotation reversed (conjugated quaternions,
transposed matrices): the comparison must fail.
"""
import argparse
import math
import os
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
from vtkmodules.vtkRenderingCore import (vtkActor, vtkGlyph3DMapper, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens
from mesolens.lens import write_png

DATA = os.environ["MESOLENS_DATA_DIR"]
OUTPUT = os.environ.get("MESOLENS_TEST_OUTPUT_DIR", ".")


def biomt_rows(k):
    """REMARK 350 BIOMT lines of copy k of the ring."""
    angle = math.radians(120.0 * k)
    c, s = math.cos(angle), math.sin(angle)
    rows = [(c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0)]
    shift = np.array(rows) @ np.array([40.0, 0.0, 0.0])
    return ["REMARK 350   BIOMT%d %3d %9.6f %9.6f %9.6f %14.5f"
            % (i + 1, k + 1, row[0], row[1], row[2], shift[i]) for i, row in enumerate(rows)]


def ring_file(two_chains=False):
    """Crambin with a three-copy REMARK 350 ring instead of its own monomer; with two_chains,
    residues 24 on are chain B, which only the first copy takes."""
    remarks = ["REMARK 350 BIOMOLECULE: 1"]
    if two_chains:
        remarks += ["REMARK 350 APPLY THE FOLLOWING TO CHAINS: A, B"] + biomt_rows(0)
        remarks += ["REMARK 350 APPLY THE FOLLOWING TO CHAINS: A"] + biomt_rows(1) + biomt_rows(2)
    else:
        remarks += ["REMARK 350 APPLY THE FOLLOWING TO CHAINS: A"]
        remarks += biomt_rows(0) + biomt_rows(1) + biomt_rows(2)
    records = []
    with open(os.path.join(DATA, "proteins", "1crn.pdb")) as crambin:
        for line in crambin:
            line = line.rstrip("\n")
            if line.startswith("REMARK 350"):
                continue
            if two_chains and line.startswith(("ATOM", "HETATM", "TER")) and len(line) > 26 \
                    and line[22:26].strip() and int(line[22:26]) >= 24:
                line = line[:21] + "B" + line[22:]
            records.append(line)
    name = "assembly_glyphs_ring_two_chains.pdb" if two_chains else "assembly_glyphs_ring.pdb"
    path = os.path.join(OUTPUT, name)
    # Tests of this script run in parallel and write the same file: each writes its own copy
    # and moves it into place, so that none reads another's half-written file.
    with tempfile.NamedTemporaryFile("w", dir=OUTPUT, suffix=".pdb", delete=False) as ring:
        ring.write("\n".join(remarks + records) + "\n")
    os.replace(ring.name, path)
    return path


def geometry(reader):
    """The ribbons and the solvent-excluded surface of the reader's atoms."""
    ribbons = mesolens.vtkMesoRibbons()
    ribbons.SetInputConnection(reader.GetOutputPort(0))
    surface = mesolens.vtkMesoMolecularSurface()
    surface.SetInputConnection(reader.GetOutputPort(0))
    surface.SetTolerance(0.5)
    return ribbons, surface


def copies_of(reader, mode):
    """The reader's copies; for wrong-orientation, with each rotation reversed."""
    reader.Update()
    copies = vtkPolyData()
    copies.DeepCopy(reader.GetOutput(1))
    if mode == "wrong-orientation":
        quaternions = vtk_to_numpy(copies.GetPointData().GetArray("AssemblyOrientation"))
        array = numpy_to_vtk(quaternions * np.array([1.0, -1.0, -1.0, -1.0]), deep=True)
        array.SetName("AssemblyOrientation")
        copies.GetPointData().AddArray(array)
        matrices = vtk_to_numpy(copies.GetPointData().GetArray("AssemblyMatrix")).reshape(-1, 3, 4)
        matrices[:, :, :3] = matrices[:, :, :3].transpose(0, 2, 1).copy()
        array = numpy_to_vtk(matrices.reshape(-1, 12), deep=True)
        array.SetName("AssemblyMatrix")
        copies.GetPointData().AddArray(array)
    return copies


def atoms_actor(mode):
    """The ring's atoms, balls and sticks, by vtkMesoAtomMapper: expanded, or the asymmetric
    unit drawn at each copy."""
    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(ring_file(two_chains=True))
    reader.SetAssembly("1")
    reader.SetExpandAssembly(mode == "expanded")
    mapper = mesolens.vtkMesoAtomMapper()
    mapper.SetInputConnection(reader.GetOutputPort(0))
    mapper.SetStyleToBallAndStick()
    if mode != "expanded":
        copies = vtkTrivialProducer()
        copies.SetOutput(copies_of(reader, mode))
        mapper.SetAssemblyConnection(copies.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    return actor


def actor_of(mode, what, path):
    """The ribbons' or the surface's actor."""
    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(path)
    reader.SetAssembly("1")
    reader.SetExpandAssembly(mode == "expanded")
    copies = None if mode == "expanded" else copies_of(reader, mode)
    ribbons, surface = geometry(reader)
    if what == "ribbons":
        source, colour = ribbons, (0.9, 0.5, 0.2)
    else:
        source, colour = surface, (0.6, 0.7, 0.9)
    if copies is None:
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(source.GetOutputPort())
    else:
        mapper = vtkGlyph3DMapper()
        mapper.SetInputData(copies)
        mapper.SetSourceConnection(source.GetOutputPort())
        mapper.SetScaling(False)
        mapper.SetOrientationModeToQuaternion()
        mapper.SetOrientationArray("AssemblyOrientation")
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*colour)
    return actor


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mode", choices=["expanded", "instanced", "wrong-orientation"],
                        required=True)
    parser.add_argument("--what", choices=["ribbons", "surface", "atoms"], required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--size", type=int, default=240)
    args = parser.parse_args()
    renderer = vtkRenderer()
    if args.what == "atoms":
        renderer.AddActor(atoms_actor(args.mode))
    else:
        renderer.AddActor(actor_of(args.mode, args.what, ring_file()))
    renderer.SetBackground(1, 1, 1)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 0, 260)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(30)
    renderer.ResetCameraClippingRange(-90, 90, -90, 90, -60, 60)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    window.Render()
    write_png(window, args.output)


if __name__ == "__main__":
    main()
