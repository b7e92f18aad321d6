# SPDX-License-Identifier: GPL-3.0-or-later
"""One run of the scaling benchmark: the DPPC patch mapped onto the mitochondrion's outer
membrane in k x k tiles, then drawn as MesoLens Atoms. Every rank writes `key value` lines to
OUTPUT_DIR/rank<r>.txt (its atoms and peak memory, from a programmable filter that runs on
every rank); rank 0 adds the times.

    [mpirun -np N] pvbatch scaling_scene.py PLUGIN DATA_DIR TILES OUTPUT_DIR
"""
import os
import sys
import time

from paraview import simple

plugin, data, tiles, output_dir = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]

# Runs on every rank: its share of the atoms and its peak resident memory so far.
REPORT = f"""
import os, resource
from vtkmodules.vtkParallelCore import vtkMultiProcessController
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
with open(os.path.join({output_dir!r}, "rank%d.txt" % rank), "a") as stream:
    stream.write("%s_atoms %d\\n" % (KEY, inputs[0].GetNumberOfPoints()))
    stream.write("%s_peak_mib %.1f\\n" % (KEY, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0))
output.ShallowCopy(inputs[0].VTKObject)
"""


def report(proxy, key):
    probe = simple.ProgrammableFilter(Input=proxy)
    probe.Script = f"KEY = {key!r}\n" + REPORT
    probe.CopyArrays = 0
    probe.UpdatePipeline()
    simple.Delete(probe)


def result(key, value):
    with open(os.path.join(output_dir, "rank0.txt"), "a", encoding="utf-8") as stream:
        stream.write(f"{key} {value}\n")


simple.LoadPlugin(plugin, remote=False)
organelle = simple.MesoLensMeshReader(FileName=os.path.join(data, "meshes", "mito5_outer_membrane.obj"))
report(organelle, "start")
membrane = simple.MesoLensGROReader(
    FileName=os.path.join(data, "membranes", "dppc128_slipids_323K.gro"))
membrane.RemoveWaters = 1
lens = simple.MembraneMapping(Surface=organelle, Membrane=membrane)
lens.SeedPoint = list(simple.servermanager.Fetch(organelle).GetPoint(1000))
lens.Tiles = tiles
lens.MembraneToMeshScale = 1e-4
lens.MappingMethod = "Polynomial"
start = time.perf_counter()
lens.UpdatePipeline()
result("mapping_s", f"{time.perf_counter() - start:.3f}")
report(lens, "mapped")

view = simple.CreateRenderView()
view.ViewSize = [1024, 768]
view.OrientationAxesVisibility = 0
atoms = simple.Show(lens, view)
atoms.SetRepresentationType("MesoLens Atoms")
atoms.RadiusScale = 1e-4
atoms.ColorArrayName = ["POINTS", ""]  # element colours
simple.ResetCamera(view)
start = time.perf_counter()
simple.Render(view)  # delivery, upload, first culling pass, compositing
first = time.perf_counter()
view.GetActiveCamera().Azimuth(10)
simple.Render(view)
result("first_frame_s", f"{first - start:.3f}")
result("next_frame_s", f"{time.perf_counter() - first:.3f}")
report(lens, "end")
