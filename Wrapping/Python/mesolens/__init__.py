# SPDX-License-Identifier: GPL-3.0-or-later
"""MesoLens: multi-scale cell visualization for VTK.

Import it next to ``vtkmodules``; every MesoLens class is available here, e.g.
``mesolens.vtkMesoStructureReader``.
"""
from .MesoLensFilters import *  # noqa: F401,F403
from .MesoLensRendering import *  # noqa: F401,F403

__version__ = "0.1.0"
