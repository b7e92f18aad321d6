#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The mesolens command: it renders, writes animation frames, and refuses bad input with one
clear line and a non-zero exit status, never a traceback.

    test_mesolens_command.py MESOLENS_COMMAND
"""
import os
import subprocess
import sys
import tempfile
import unittest

COMMAND = sys.argv.pop(1) if len(sys.argv) > 1 else "mesolens"
DATA = os.environ.get("MESOLENS_DATA_DIR", "Data")
MESH = os.path.join(DATA, "meshes", "mito5_outer_membrane.obj")
PATCH = os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro")
YIIP = os.path.join(DATA, "membranes", "yiip_popepopg.gro")
YIIP_XTC = os.path.join(DATA, "membranes", "yiip_popepopg.xtc")
# A stem cell's membrane whose triangles (up to 8 µm) dwarf a patch.
COARSE_CELL = os.path.join(DATA, "meshes", "hipsc_cell_membrane_1.obj")


def run(*arguments, environment=None):
    result = subprocess.run([COMMAND, *arguments], capture_output=True, text=True, timeout=300,
                            check=False, env=environment)
    return result.returncode, result.stderr


class MesolensCommand(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.output = os.path.join(self.folder.name, "out.png")

    def tearDown(self):
        self.folder.cleanup()

    def refused(self, expected_status, message, *arguments):
        status, errors = run(*arguments)
        self.assertEqual(status, expected_status, errors)
        self.assertIn(message, errors)
        self.assertNotIn("Traceback", errors)
        self.assertFalse(os.path.exists(self.output))

    def render(self, *arguments):
        return ("render", "--mesh", MESH, "--membrane", PATCH, "--size", "64x48", "--quiet",
                "-o", self.output, *arguments)

    def test_renders_each_method_and_style(self):
        for method in ("polynomial", "instancing", "displacement"):
            for style in ("space-filling", "ball-and-stick"):
                status, errors = run(*self.render("--vertex", "1000", "--tiles", "2",
                                                  "--method", method, "--style", style))
                self.assertEqual(status, 0, errors)
                self.assertGreater(os.path.getsize(self.output), 100)
                os.remove(self.output)

    def test_ambient_occlusion_and_shadows(self):
        for effects in (["--ssao"], ["--shadows"], ["--ssao", "--shadows"]):
            status, errors = run(*self.render("--vertex", "1000", "--tiles", "1", *effects))
            self.assertEqual(status, 0, errors)
            self.assertGreater(os.path.getsize(self.output), 100)
            os.remove(self.output)

    def test_camera_file(self):
        camera = os.path.join(self.folder.name, "camera.txt")
        with open(camera, "w", encoding="ascii") as file:
            file.write("# a view of vertex 1000 from outside\nposition 4.0 0.8 0.7\n"
                       "focal 1.97 0.77 0.71\nup 0 0 1\nangle 1\n")
        status, errors = run(*self.render("--vertex", "1000", "--camera", camera))
        self.assertEqual(status, 0, errors)
        os.remove(self.output)
        with open(camera, "a", encoding="ascii") as file:
            file.write("zoom 2\n")
        self.refused(1, "line 6: cannot read 'zoom 2'",
                     *self.render("--vertex", "1000", "--camera", camera))
        with open(camera, "w", encoding="ascii") as file:
            file.write("position nan 0 0\n")
        self.refused(1, "line 1: not a finite number",
                     *self.render("--vertex", "1000", "--camera", camera))

    def test_coarse_cell_shows_the_mapped_atoms(self):
        # On a mesh whose triangles are far larger than the patch, the atoms lie on its smooth
        # surface and the picture shows them (and says how many were mapped).
        arguments = [a for a in self.render("--vertex", "1000", "--tiles", "3")
                     if a != "--quiet"]
        arguments[arguments.index(MESH)] = COARSE_CELL
        arguments[arguments.index("64x48")] = "160x120"
        status, errors = run(*arguments)
        self.assertEqual(status, 0, errors)
        self.assertIn("3 x 3 tiles", errors)
        self.assertRegex(errors, r"wrote .*: [0-9,]+ atoms")
        from vtkmodules.vtkIOImage import vtkPNGReader
        from vtkmodules.util.numpy_support import vtk_to_numpy
        reader = vtkPNGReader()
        reader.SetFileName(self.output)
        reader.Update()
        pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3]
        # Atoms are coloured by element: red oxygens and blue nitrogens are not on the grey cell.
        colourful = ((pixels.max(axis=1).astype(int) - pixels.min(axis=1)) > 60).sum()
        self.assertGreater(colourful, 100)

    def test_progress_times_count_from_the_start(self):
        arguments = [a for a in self.render("--vertex", "1000", "--tiles", "1") if a != "--quiet"]
        status, errors = run(*arguments)
        self.assertEqual(status, 0, errors)
        times = [float(line.split("[")[1].split("s]")[0]) for line in errors.splitlines()
                 if line.startswith("mesolens: [")]
        self.assertGreaterEqual(len(times), 4)
        self.assertEqual(times, sorted(times))

    def test_a_camera_that_misses_the_patch_is_refused(self):
        camera = os.path.join(self.folder.name, "away.txt")
        with open(camera, "w", encoding="ascii") as file:
            file.write("position 4.0 0.8 0.7\nfocal 6.0 0.8 0.7\nup 0 0 1\nangle 20\n")
        self.refused(1, "does not show in the camera file's view",
                     *self.render("--vertex", "1000", "--camera", camera))

    def test_writes_a_frame_per_time_step(self):
        status, errors = run("render", "--mesh", MESH, "--membrane", YIIP, "--trajectory",
                             YIIP_XTC, "--vertex", "1000", "--tiles", "1", "--frames", "2",
                             "--size", "64x48", "--quiet", "-o", self.output)
        self.assertEqual(status, 0, errors)
        frames = [os.path.join(self.folder.name, f"out_{i:04d}.png") for i in range(2)]
        for frame in frames:
            self.assertTrue(os.path.isfile(frame), frame)

    def test_missing_and_unreadable_files(self):
        self.refused(1, "mesh '/nowhere/cell.obj' does not exist", "render", "--mesh",
                     "/nowhere/cell.obj", "--membrane", PATCH, "--vertex", "0", "-o", self.output)
        self.refused(1, "membrane '/nowhere/patch.gro' does not exist", "render", "--mesh", MESH,
                     "--membrane", "/nowhere/patch.gro", "--vertex", "0", "-o", self.output)
        garbage = os.path.join(self.folder.name, "garbage.obj")
        with open(garbage, "wb") as file:
            file.write(bytes(range(256)) * 8)
        self.refused(1, "mesh", "render", "--mesh", garbage, "--membrane", PATCH,
                     "--vertex", "0", "-o", self.output)
        truncated = os.path.join(self.folder.name, "truncated.gro")
        with open(PATCH, encoding="ascii") as source, open(truncated, "w", encoding="ascii") as copy:
            copy.write(source.read()[:5000])
        self.refused(1, "cannot read the membrane", "render", "--mesh", MESH, "--membrane",
                     truncated, "--vertex", "0", "-o", self.output)

    def test_view_without_a_display_says_so(self):
        environment = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
        status, errors = run("view", "--mesh", MESH, "--membrane", PATCH, environment=environment)
        self.assertEqual(status, 1, errors)
        self.assertIn("view needs a display", errors)
        self.assertNotIn("Traceback", errors)

    def test_cut_open(self):
        atoms = {}
        for cut in ([], ["--cut", "0.5"], ["--cut", "0.5", "--cut-order", "random"],
                    ["--cut", "1", "--cut-order", "inverted"]):
            arguments = [a for a in self.render("--vertex", "1000", "--tiles", "2", *cut)
                         if a != "--quiet"]
            status, errors = run(*arguments)
            self.assertEqual(status, 0, errors)
            self.assertGreater(os.path.getsize(self.output), 100)
            os.remove(self.output)
            atoms[" ".join(cut)] = int(errors.split("wrote ")[1].split(": ")[1].split(" atoms")[0])
        whole = atoms[""]
        self.assertLess(atoms["--cut 0.5"], whole)
        self.assertGreater(atoms["--cut 0.5"], whole // 2)
        self.assertLess(abs(atoms["--cut 0.5 --cut-order random"] - atoms["--cut 0.5"]), whole // 50)
        self.assertLess(atoms["--cut 1 --cut-order inverted"], atoms["--cut 0.5"])
        self.refused(1, "--cut must be between 0 and 1", *self.render("--vertex", "1000", "--cut", "2"))

    def test_centre_off_the_surface_gives_the_mapping_reason(self):
        self.refused(1, "the membrane cannot be mapped there:", *self.render("--center", "50,50,50"))

    def test_out_of_range_arguments(self):
        self.refused(1, "tiles must be between 1 and 15", *self.render("--vertex", "0", "--tiles", "0"))
        self.refused(1, "is not a vertex of the mesh", *self.render("--vertex", "99999999"))
        self.refused(2, "expected X,Y,Z", *self.render("--center", "1,2"))
        self.refused(2, "WIDTHxHEIGHT", *self.render("--vertex", "0", "--size", "0x0"))
        self.refused(1, "--frames needs a trajectory", *self.render("--vertex", "1000", "--frames", "2"))
        status, errors = run("render", "--mesh", MESH, "--membrane", PATCH, "--vertex", "1000",
                             "--quiet", "-o", "/nowhere/out.png")
        self.assertEqual(status, 1, errors)
        self.assertIn("no folder", errors)


if __name__ == "__main__":
    unittest.main()
