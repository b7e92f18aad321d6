# SPDX-License-Identifier: GPL-3.0-or-later
"""The client of test_pvserver.py (pvpython): connects to a pvserver on MPI ranks, loads the
plugin on both sides, and checks that the server's ranks share the atoms, that DSSP runs there,
and that the composited picture of MesoLens Atoms comes back.

    pvpython pvserver_client.py PORT PLUGIN DATA_DIR IMAGE
"""
import os
import sys
import time

from paraview import simple

port, plugin, data, image = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
for attempt in range(60):  # the server may still be starting
    try:
        if simple.Connect("localhost", port):
            break
    except RuntimeError:
        pass
    time.sleep(1)
else:
    raise SystemExit("no pvserver answered")
simple.LoadPlugin(plugin, remote=False)
simple.LoadPlugin(plugin, remote=True)
protein = simple.MesoLensStructureReader(FileName=os.path.join(data, "proteins", "1hpv.pdb"))
structure = simple.SecondaryStructureDSSP(Input=protein)
ranks = simple.ProcessIdScalars(Input=structure)
ranks.UpdatePipeline()
process_ids = ranks.GetPointDataInformation().GetArray("ProcessId").GetRange()
view = simple.CreateRenderView()
view.ViewSize = [320, 240]
atoms = simple.Show(structure, view)
atoms.SetRepresentationType("MesoLens Atoms")
atoms.ColorArrayName = ["POINTS", ""]
simple.Render(view)
simple.SaveScreenshot(image, view, ImageResolution=[320, 240])
failures = []
if process_ids != (0.0, 1.0):
    failures.append(f"the atoms are on ranks {process_ids}, not on both")
if structure.GetDataInformation().GetNumberOfPoints() != protein.GetDataInformation().GetNumberOfPoints():
    failures.append("DSSP on the server lost atoms")
if not os.path.exists(image) or os.path.getsize(image) < 1000:
    failures.append("no picture came back")
for failure in failures:
    print("FAIL:", failure)
simple.Delete(view)  # before the connection goes: the view's GL context lives on the client
del view
simple.Disconnect()
print("pvserver checks", "failed" if failures else "passed")
sys.exit(1 if failures else 0)
