# SPDX-License-Identifier: GPL-3.0-or-later
"""A protein in ParaView, three ways at once: HIV-1 protease (1hpv) as ribbons from its
secondary structure (one colour per helix, strand or loop), its inhibitor as balls and sticks
picked out by ParaView's Threshold, and its molecular surface, translucent. Runs in pvpython or
pvbatch (on MPI ranks too):

    pvpython protein_views.py PLUGIN [IMAGE]

PLUGIN is the built MesoLens.so (build/lib/paraview-5.11/plugins/MesoLens/MesoLens.so); the
picture goes to IMAGE (default protein_views.png). Data come from the repository's Data/.
"""
import os
import sys

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.environ.get("MESOLENS_DATA_DIR", os.path.join(HERE, "..", "..", "Data"))
plugin = sys.argv[1]
image = sys.argv[2] if len(sys.argv) > 2 else "protein_views.png"

simple.LoadPlugin(plugin, remote=False)
protease = simple.MesoLensStructureReader(FileName=os.path.join(DATA, "proteins", "1hpv.pdb"))
protease.RemoveWaters = 1
structure = simple.SecondaryStructureDSSP(Input=protease)
ribbons = simple.Ribbons(Input=structure)
# The inhibitor: the atoms the file marks HETATM (waters are gone), with their bonds.
inhibitor = simple.Threshold(Input=protease, Scalars=["POINTS", "IsHetAtm"])
inhibitor.LowerThreshold, inhibitor.UpperThreshold = 1, 1
surface = simple.MolecularSurface(Input=protease)

view = simple.CreateRenderView()
view.ViewSize = [640, 480]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:  # ParaView 5.11 paints the background from its palette unless told not to
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
cartoon = simple.Show(ribbons, view)
simple.ColorBy(cartoon, ("POINTS", "SecondaryStructureId"))
cartoon_colours = simple.GetColorTransferFunction("SecondaryStructureId")
cartoon_colours.ApplyPreset("Rainbow Uniform", True)
ligand = simple.Show(inhibitor, view)
ligand.SetRepresentationType("MesoLens Atoms")
ligand.Style = "Ball And Stick"
ligand.ColorArrayName = ["POINTS", ""]  # element colours
skin = simple.Show(surface, view)
skin.ColorArrayName = ["POINTS", ""]
skin.DiffuseColor = [0.75, 0.8, 0.9]
skin.Opacity = 0.25

simple.Render(view)  # frames everything
view.CameraPosition = [view.CameraFocalPoint[0], view.CameraFocalPoint[1],
                       view.CameraFocalPoint[2] + 90.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
simple.Render(view)
simple.SaveScreenshot(image, view, ImageResolution=[640, 480])
print("wrote", image)
