#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Walk an MD trajectory with MesoLens' temporal reader and measure the bilayer thickness
(distance between the mean phosphorus heights of the two leaflets) in every frame.

    membrane_thickness.py [TOPOLOGY.gro TRAJECTORY.xtc]
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

import mesolens
from mesolens import array_names

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))


def main():
    topology = sys.argv[1] if len(sys.argv) > 2 else os.path.join(DATA, "membranes", "yiip_popepopg.gro")
    trajectory = sys.argv[2] if len(sys.argv) > 2 else os.path.join(DATA, "membranes", "yiip_popepopg.xtc")
    reader = mesolens.vtkMesoTrajectoryReader()
    reader.SetTopologyFileName(topology)
    reader.SetTrajectoryFileName(trajectory)
    reader.UpdateInformation()
    times = reader.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
    print(f"{trajectory}: {len(times)} frames of {reader.GetNumberOfTopologyAtoms()} atoms")
    for time in times:
        reader.UpdateTimeStep(time)
        atoms = reader.GetOutput()
        names = atoms.GetPointData().GetAbstractArray(array_names.AtomName)
        phosphorus = np.array([names.GetValue(i) == "P" for i in range(names.GetNumberOfValues())])
        z = vtk_to_numpy(atoms.GetPoints().GetData())[phosphorus, 2]
        middle = np.median(z)
        thickness = z[z > middle].mean() - z[z <= middle].mean()
        print(f"  t = {time / 1000:6.1f} ns: {phosphorus.sum()} P atoms, P-P thickness {thickness:5.2f} Å")


if __name__ == "__main__":
    main()
