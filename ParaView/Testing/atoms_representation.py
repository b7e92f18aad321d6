# SPDX-License-Identifier: GPL-3.0-or-later
"""The "MesoLens Atoms" representation in ParaView's render view, for its image test: crambin
three times, space-filling in element colours, balls and sticks coloured by B-factor through
ParaView's colour map, and translucent sticks, with the view's ambient occlusion on.

Run as: pvbatch atoms_representation.py PLUGIN_LIBRARY IMAGE DATA_DIR
"""
import os
import sys

from paraview import simple

plugin, image, data = sys.argv[1:4]
simple.LoadPlugin(plugin, remote=False)
path = os.path.join(data, "proteins", "1crn.pdb")

view = simple.CreateRenderView()
view.ViewSize = [600, 300]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:  # ParaView 5.11 paints the background from its palette unless told not to
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.UseAmbientOcclusion = 1  # the property UseSSAO

styles = (("Space Filling", None, 1.0), ("Ball And Stick", "BFactor", 1.0), ("Sticks", None, 0.5))
for index, (style, array, opacity) in enumerate(styles):
    crambin = simple.MesoLensStructureReader(FileName=path)  # one display per source and view
    display = simple.Show(crambin, view)
    display.SetRepresentationType("MesoLens Atoms")
    display.Style = style
    display.Position = [36.0 * index, 0.0, 0.0]  # side by side, along x
    display.Opacity = opacity
    if array:
        simple.ColorBy(display, ("POINTS", array))
        simple.GetColorTransferFunction(array).ApplyPreset("Cool to Warm", True)
    else:
        simple.ColorBy(display, None)  # element colours

simple.ResetCamera(view)
view.CameraParallelProjection = 1  # the three side by side, equally large
simple.ResetCamera(view)
view.CameraParallelScale = 27.0  # Å: half the view's height, the three fill its width
simple.Render(view)
simple.SaveScreenshot(image, view, ImageResolution=view.ViewSize)
print("wrote", image)
