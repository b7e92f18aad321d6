#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draw atoms with MesoLens' impostor mapper, off screen, to PNGs.

1. A protein from Data/ (ubiquitin, 1UBQ) in each style: space-filling, balls and sticks,
   sticks; element colours, exact per-pixel spheres and cylinders.
2. The all-atom DPPC patch of Data/ tiled 4 x 4 on the mitochondrion's outer membrane (µm) by
   the quadratic warp of the membrane mapping, evaluated per atom on the GPU from one copy of
   the patch, with ambient occlusion (SSAO) and shadows cast by a light over the organelle.

    render_atoms.py [--output-prefix atoms] [--size 600] [--tiles 4]
"""
import argparse
import os

import numpy as np
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
ANGSTROM_TO_MICROMETRE = 1e-4
STYLES = {"space_filling": mesolens.vtkMesoAtomMapper.SPACE_FILLING,
          "ball_and_stick": mesolens.vtkMesoAtomMapper.BALL_AND_STICK,
          "sticks": mesolens.vtkMesoAtomMapper.STICKS}


def window_of(renderer, size):
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    return window


def save(window, path):
    window.Render()
    capture = vtkWindowToImageFilter()
    capture.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    print("wrote", path)


def protein_styles(prefix, size):
    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(os.path.join(DATA, "proteins", "1ubq.pdb"))
    for name, style in STYLES.items():
        mapper = mesolens.vtkMesoAtomMapper()
        mapper.SetInputConnection(reader.GetOutputPort())
        mapper.SetStyle(style)
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        renderer.SetBackground(0.1, 0.11, 0.14)
        renderer.ResetCamera()
        renderer.GetActiveCamera().Zoom(1.3)
        save(window_of(renderer, size), f"{prefix}_protein_{name}.png")


def mapped_membrane(prefix, size, tiles):
    surface = mesolens.vtkMesoMeshReader()
    surface.SetFileName(os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"))
    surface.Update()
    membrane = mesolens.vtkMesoTrajectoryReader()
    membrane.SetTopologyFileName(os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro"))
    membrane.RemoveWatersOn()
    # The warp only: the mapper evaluates it per atom and tile on the GPU.
    mapping = mesolens.vtkMesoMembraneMapping()
    mapping.SetSurfaceConnection(surface.GetOutputPort())
    mapping.SetMembraneConnection(membrane.GetOutputPort())
    mapping.SetSeedPoint(surface.GetOutput().GetPoint(1000))
    mapping.SetTiles(tiles)
    mapping.SetMembraneToMeshScale(ANGSTROM_TO_MICROMETRE)
    mapping.SetMappingMethodToPolynomial()
    mapping.OutputAtomsOff()
    if not mapping.GetExecutive().Update():
        raise SystemExit("the membrane mapping failed")

    atoms = mesolens.vtkMesoAtomMapper()
    atoms.SetInputConnection(membrane.GetOutputPort())
    atoms.SetWarpConnection(mapping.GetOutputPort())
    atoms.SetRadiusScale(ANGSTROM_TO_MICROMETRE)
    atoms_actor = vtkActor()
    atoms_actor.SetMapper(atoms)
    organelle = vtkPolyDataMapper()
    organelle.SetInputConnection(surface.GetOutputPort())
    organelle.ScalarVisibilityOff()
    organelle_actor = vtkActor()
    organelle_actor.SetMapper(organelle)
    organelle_actor.GetProperty().SetColor(0.75, 0.72, 0.68)

    renderer = vtkRenderer()
    renderer.AddActor(organelle_actor)
    renderer.AddActor(atoms_actor)
    renderer.SetBackground(0.1, 0.11, 0.14)
    bounds = atoms.GetBounds()
    centre = np.array([(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
                       (bounds[4] + bounds[5]) / 2])
    normal = centre - np.array(surface.GetOutput().GetCenter())
    normal /= np.linalg.norm(normal)
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*(centre + 0.05 * normal))
    camera.SetViewUp(0, 0, 1)
    camera.Azimuth(25)
    renderer.ResetCameraClippingRange()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    side = np.cross(normal, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    light.SetPosition(*(centre + 0.03 * normal + 0.03 * side))
    light.SetFocalPoint(*centre)
    light.PositionalOn()
    light.SetConeAngle(70)
    renderer.AddLight(light)

    # Shadows from the light, then ambient occlusion over the lit picture's geometry.
    effects = mesolens.vtkMesoRenderPasses()
    effects.ShadowsOn()
    effects.SetShadowMapResolution(2048)
    effects.SSAOOn()
    effects.SetSSAORadius(4 * ANGSTROM_TO_MICROMETRE)
    effects.SetSSAOBias(0.5 * ANGSTROM_TO_MICROMETRE)
    effects.SetSSAOKernelSize(64)
    effects.SSAOBlurOn()
    effects.Apply(renderer)
    save(window_of(renderer, size), f"{prefix}_membrane_ssao_shadows.png")

    # The same without the passes, for comparison.
    effects.ShadowsOff()
    effects.SSAOOff()
    effects.Apply(renderer)
    save(window_of(renderer, size), f"{prefix}_membrane_plain.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output-prefix", default="atoms")
    parser.add_argument("--size", type=int, default=600)
    parser.add_argument("--tiles", type=int, default=4)
    args = parser.parse_args()
    protein_styles(args.output_prefix, args.size)
    mapped_membrane(args.output_prefix, args.size, args.tiles)


if __name__ == "__main__":
    main()
