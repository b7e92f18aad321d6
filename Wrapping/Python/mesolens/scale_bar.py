# SPDX-License-Identifier: GPL-3.0-or-later
"""A scale bar that follows the zoom: a bar of a round length (1, 2 or 5 times a power of ten,
in Å, nm or µm) at the lower right of a renderer's viewport, measured at the depth of the
camera's focal point."""
import math

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkActor2D, vtkPolyDataMapper2D, vtkTextActor

from .camera import pixel_size

# The bar's length on screen: a round length of at most this many pixels, and of at most this
# share of the viewport's width.
LONGEST_BAR = 150.0
LONGEST_SHARE = 0.4
MARGIN = 12  # pixels from the viewport's right edge


def round_length(longest):
    """The largest of 1, 2, 5 times a power of ten that is at most `longest` (> 0)."""
    power = 10.0 ** math.floor(math.log10(longest))
    for step in (5.0, 2.0, 1.0):
        if step * power <= longest * (1 + 1e-9):
            return step * power
    return power


def length_label(angstrom):
    """A length in Å as people write it: Å below 1 nm, nm below 1 µm, then µm."""
    if angstrom >= 1e4:
        value, unit = angstrom / 1e4, "µm"
    elif angstrom >= 10:
        value, unit = angstrom / 10, "nm"
    else:
        value, unit = angstrom, "Å"
    return f"{value:.3g} {unit}"


class ScaleBar:
    """A scale bar in `renderer` for a scene in `units_per_angstrom` world units per Å, its bar
    `bottom` pixels above the viewport's lower edge. Call update() before each frame (the lens
    viewer does it on the renderer's StartEvent)."""

    def __init__(self, renderer, units_per_angstrom, bottom=16):
        self.renderer = renderer
        self.units_per_angstrom = units_per_angstrom
        self.bottom = bottom
        self._points = vtkPoints()
        self._points.SetNumberOfPoints(6)
        lines = vtkCellArray()
        for a, b in ((0, 1), (2, 3), (4, 5)):  # the bar and its two end ticks
            lines.InsertNextCell(2)
            lines.InsertCellPoint(a)
            lines.InsertCellPoint(b)
        bar = vtkPolyData()
        bar.SetPoints(self._points)
        bar.SetLines(lines)
        mapper = vtkPolyDataMapper2D()
        mapper.SetInputData(bar)
        self.bar = vtkActor2D()
        self.bar.SetMapper(mapper)
        self.bar.GetProperty().SetColor(0.95, 0.95, 0.95)
        self.bar.GetProperty().SetLineWidth(2)
        self.label = vtkTextActor()
        text = self.label.GetTextProperty()
        text.SetFontSize(14)
        text.SetColor(0.95, 0.95, 0.95)
        text.SetJustificationToCentered()
        text.ShadowOn()  # readable over light atoms and surfaces too
        renderer.AddActor2D(self.bar)
        renderer.AddActor2D(self.label)
        self.angstrom = None  # the length shown, Å

    def angstrom_per_pixel(self):
        return pixel_size(self.renderer) / self.units_per_angstrom

    def update(self):
        per_pixel = self.angstrom_per_pixel()
        if not per_pixel > 0 or not math.isfinite(per_pixel):
            self.bar.VisibilityOff()
            self.label.VisibilityOff()
            return
        width, _ = self.renderer.GetSize()
        self.angstrom = round_length(min(LONGEST_BAR, LONGEST_SHARE * width) * per_pixel)
        pixels = self.angstrom / per_pixel
        right = width - MARGIN
        left = right - pixels
        y = self.bottom
        for index, point in enumerate(((left, y), (right, y), (left, y - 4), (left, y + 4),
                                       (right, y - 4), (right, y + 4))):
            self._points.SetPoint(index, point[0], point[1], 0.0)
        self._points.Modified()
        self.label.SetInput(length_label(self.angstrom))
        self.label.SetPosition((left + right) / 2, y + 6)
        self.bar.VisibilityOn()
        self.label.VisibilityOn()

    def remove(self):
        self.renderer.RemoveActor2D(self.bar)
        self.renderer.RemoveActor2D(self.label)
