# SPDX-License-Identifier: GPL-3.0-or-later
"""scripts/check_layers.py: the source tree keeps its layers, and every rule fires on a tree
that breaks it."""
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(SOURCE, "scripts", "check_layers.py")

# A small tree that keeps the layers: one Core subsystem with a private file, one module each.
CLEAN = {
    "Core/include/mesolens/mesh/triangle_mesh.h": '#include "mesolens/common/errors.h"\n#include <vector>\n',
    "Core/include/mesolens/common/errors.h": "#include <stdexcept>\n",
    "Core/mesh/triangle_mesh.cpp": '#include "mesolens/mesh/triangle_mesh.h"\n#include "mesh/detail/edges.h"\n#include "common/detail/grid.h"\n#include <Eigen/Core>\n',
    "Core/mesh/detail/edges.h": "#include <Eigen/Core>\n",
    "Core/common/detail/grid.h": "#include <array>\n",
    "Testing/Core/mesh/test_edges.cpp": '#include "mesh/detail/edges.h"\n',
    "Filters/CMakeLists.txt": "set(classes\n  vtkMesoReader)\nvtk_module_add_module(X CLASSES ${classes}\n  NOWRAP_HEADERS vtkMesoNames.h\n  PRIVATE_HEADERS vtkMesoConversion.h)\n",
    "Filters/vtkMesoNames.h": "",
    "Filters/vtkMesoReader.h": '#include "vtkPolyDataAlgorithm.h"\n',
    "Filters/vtkMesoReader.cxx": '#include "vtkMesoReader.h"\n#include "vtkMesoConversion.h"\n#include <gemmi/model.hpp>\n',
    "Filters/vtkMesoConversion.h": '#include "mesolens/mesh/triangle_mesh.h"\n',
    "Rendering/CMakeLists.txt": "vtk_module_add_module(Y\n  CLASSES vtkMesoMapper\n  SOURCES x.cxx)\n",
    "Rendering/vtkMesoMapper.h": '#include "vtkOpenGLPolyDataMapper.h"\n',
    "Rendering/vtkMesoMapper.cxx": '#include "vtkMesoMapper.h"\n#include "vtkMesoReader.h"\n#include "vtkMesoNames.h"\n',
    "Rendering/Testing/Cxx/TestMapper.cxx": '#include "vtkMesoConversion.h"\n',
}

# Each breach, as (file, its text, a phrase the report must contain).
BREACHES = [
    ("Core/mesh/uses_vtk.cpp", '#include "vtkPolyData.h"\n', "Core includes VTK"),
    ("Core/mesh/uses_module.cpp", '#include "vtkMesoReader.h"\n', "Core includes VTK"),
    ("Core/include/mesolens/mesh/eigen.h", "#include <Eigen/Core>\n", "third-party header"),
    ("Core/include/mesolens/mesh/private.h", '#include "mesh/detail/edges.h"\n', "private file"),
    ("Core/cutaway/reach.cpp", '#include "mesh/detail/edges.h"\n', "cutaway includes a private file of mesh"),
    ("Testing/Core/cutaway/test_reach.cpp", '#include "mesh/detail/edges.h"\n', "cutaway includes a private file of mesh"),
    ("Filters/vtkMesoOther.cxx", '#include "mesh/detail/edges.h"\n', "private Core file is included outside Core"),
    ("Rendering/vtkMesoLeak.cxx", '#include "vtkMesoConversion.h"\n', "Rendering includes a private header of Filters"),
    ("Core/vtk.module", "NAME MesoLens::MesoLensCore\n", "plain library"),
    ("Filters/vtkMesoReader.h", '#include "vtkPolyDataAlgorithm.h"\n#include <CGAL/Simple_cartesian.h>\n', "public VTK header includes a third-party header"),
]


def write_tree(root, files):
    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8") as out:
            out.write(text)


def run(root):
    result = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True,
                            check=False)
    return result.returncode, result.stdout


class Layers(unittest.TestCase):
    def test_the_source_tree_keeps_its_layers(self):
        status, output = run(SOURCE)
        self.assertEqual(status, 0, output)

    def test_a_tree_that_keeps_them_passes(self):
        with tempfile.TemporaryDirectory() as root:
            write_tree(root, CLEAN)
            status, output = run(root)
            self.assertEqual(status, 0, output)

    def test_every_breach_is_reported(self):
        for path, text, phrase in BREACHES:
            with self.subTest(path=path), tempfile.TemporaryDirectory() as root:
                write_tree(root, CLEAN)
                write_tree(root, {path: text})
                status, output = run(root)
                self.assertEqual(status, 1, output)
                self.assertIn(phrase, output)
                self.assertIn(path, output)


if __name__ == "__main__":
    unittest.main()
