# SPDX-License-Identifier: GPL-3.0-or-later
"""The MesoLens scene: a cell surface with a membrane patch mapped onto it around a point.

``MembraneLens`` reads a cell-component mesh and a membrane patch (a structure or topology file,
optionally with a trajectory), maps the patch onto the surface around a centre point with
``vtkMesoMembraneMapping`` and draws both: the surface Phong-shaded, the atoms through
``vtkMesoAtomMapper`` (warped on the GPU for the polynomial and instancing methods, mapped on the
CPU for displacement). The ``mesolens`` command is built on it.

With the structured cutaway on (``set_cutaway``), the mapped atoms go through
``vtkMesoStructuredCutaway``: a plane cuts the membrane open, and of the molecules on the plane's
cut side a fraction is hidden so that what remains follows a wireframe of a regular triangle mesh
laid on the surface around the lens (or its patches, or a random selection for comparison).

Units: the mesh in ``mesh_unit_angstrom`` Å per unit (1e4 for µm, the default; 10 for nm); the
membrane in Å (GROMACS files are converted by the reader).
"""
import math
import os

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPlane, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFeatureEdges, vtkPolyDataNormals
from vtkmodules.vtkFiltersGeneral import vtkWarpVector
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

from . import array_names
from .camera import patch_pose, whole_pose
from .MesoLensFilters import (vtkMesoMembraneMapping, vtkMesoMeshReader,
                              vtkMesoStructureReader, vtkMesoStructuredCutaway,
                              vtkMesoTrajectoryReader, vtkMesoTrajectoryRefinement)
from .MesoLensRendering import vtkMesoAtomMapper, vtkMesoRenderPasses

METHODS = {"displacement": vtkMesoMembraneMapping.DISPLACEMENT,
           "instancing": vtkMesoMembraneMapping.MOLECULE_INSTANCING,
           "polynomial": vtkMesoMembraneMapping.POLYNOMIAL}
STYLES = {"space-filling": vtkMesoAtomMapper.SPACE_FILLING,
          "ball-and-stick": vtkMesoAtomMapper.BALL_AND_STICK}
TRAJECTORY_SUFFIXES = (".xtc", ".trr")
# Edge of the cutaway's structure triangles, Å: several lipids (about 0.65 nm² each) per
# triangle and leaflet, so that a half-hidden cut shows the wireframe, not single molecules.
CUT_STRUCTURE_EDGE = 40.0
# The lens' outline is drawn this far outside the surface, Å: above a bilayer's outer leaflet
# (about 25 Å from its midplane), so that the atoms do not hide it.
OUTLINE_LIFT = 40.0


class LensError(RuntimeError):
    """A lens that cannot be built or placed, with the reason in words."""


class _ErrorCatcher:
    """Collects the error messages an algorithm reports (its ErrorEvent) instead of printing."""

    def __init__(self, algorithm):
        self.messages = []
        algorithm.AddObserver(vtkCommand.ErrorEvent, self._record)
        algorithm.GetExecutive().AddObserver(vtkCommand.ErrorEvent, self._record)

    @calldata_type(VTK_STRING)
    def _record(self, _caller, _event, message=None):
        if message:
            # VTK's text is "ERROR: In file, line N\nclass (address): reason"; the executive's
            # "returned failure for request" follows every failure and says nothing more.
            reason = message.strip().split("): ", 1)[-1].split("\n", 1)[0]
            if "returned failure for request" not in reason:
                self.messages.append(reason)

    def take(self):
        text = "; ".join(dict.fromkeys(self.messages))
        self.messages = []
        return text


def write_png(window, path):
    """Writes what `window` (a vtkRenderWindow) shows to the PNG file `path`. Raises LensError
    when the folder does not exist or the file cannot be written."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise LensError(f"cannot write {path!r}: no folder {directory!r}")
    capture = vtkWindowToImageFilter()
    capture.SetInput(window)
    capture.ReadFrontBufferOff()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    if not os.path.isfile(path):
        raise LensError(f"cannot write {path!r}")


def read_camera_file(path, camera):
    """Sets `camera` (a vtkCamera) from a file of "position x y z", "focal x y z", "up x y z" and
    "angle degrees" lines (# comments; what write_camera_file writes). Raises LensError naming
    the line it cannot read."""
    keys = {"position": camera.SetPosition, "focal": camera.SetFocalPoint,
            "up": camera.SetViewUp}
    try:
        with open(path, encoding="utf-8") as lines:
            for number, line in enumerate(lines, 1):
                words = line.split()
                if not words or words[0].startswith("#"):
                    continue
                if not all(math.isfinite(float(w)) for w in words[1:]):
                    raise LensError(f"camera file {path!r}, line {number}: not a finite number")
                if words[0] in keys and len(words) == 4:
                    keys[words[0]](*[float(w) for w in words[1:]])
                elif words[0] == "angle" and len(words) == 2:
                    camera.SetViewAngle(float(words[1]))
                else:
                    raise LensError(f"camera file {path!r}, line {number}: cannot read {line.strip()!r}")
    except (OSError, ValueError) as error:
        raise LensError(f"cannot read the camera file {path!r}: {error}") from None


def write_camera_file(path, camera):
    """Writes `camera` (a vtkCamera) as the lines read_camera_file reads."""
    with open(path, "w", encoding="ascii") as file:
        file.write("position {} {} {}\n".format(*camera.GetPosition()))
        file.write("focal {} {} {}\n".format(*camera.GetFocalPoint()))
        file.write("up {} {} {}\n".format(*camera.GetViewUp()))
        file.write(f"angle {camera.GetViewAngle()}\n")


def _require_file(path, what):
    if not path:
        raise LensError(f"no {what} given")
    if not os.path.isfile(path):
        raise LensError(f"{what} {path!r} does not exist or is not a file")
    if not os.access(path, os.R_OK):
        raise LensError(f"{what} {path!r} is not readable")


class MembraneLens:
    """A cell surface and a membrane patch mapped onto it; see the module's description.

    mesh, membrane: file names (mesh: OBJ, PLY, STL, VTP, OFF; membrane: PDB, mmCIF or GRO).
    trajectory: XTC or TRR file over the membrane's topology, or None.
    Raises LensError with the reason when a file cannot be read.
    """

    def __init__(self, mesh, membrane, trajectory=None, mesh_unit_angstrom=1e4, progress=None):
        _require_file(mesh, "mesh")
        _require_file(membrane, "membrane")
        if trajectory:
            _require_file(trajectory, "trajectory")
        self.has_trajectory = bool(trajectory)
        self._progress = progress or (lambda text: None)
        self.scale = 1.0 / mesh_unit_angstrom  # mesh units per Å

        self._progress(f"reading the mesh {mesh}")
        self.surface = vtkMesoMeshReader()
        self.surface.SetFileName(mesh)
        self._read(self.surface, "mesh", mesh)
        if self.surface.GetOutput().GetNumberOfCells() == 0:
            raise LensError(f"mesh {mesh!r} has no triangles")

        self._progress(f"reading the membrane {membrane}")
        if membrane.lower().endswith(".gro") or trajectory:
            self.membrane = vtkMesoTrajectoryReader()
            self.membrane.SetTopologyFileName(membrane)
            if trajectory:
                self.membrane.SetTrajectoryFileName(trajectory)
        else:
            self.membrane = vtkMesoStructureReader()
            self.membrane.SetFileName(membrane)
        self.membrane.RemoveWatersOn()
        self._read(self.membrane, "membrane", trajectory or membrane)
        if self.membrane.GetOutput().GetNumberOfPoints() == 0:
            raise LensError(f"membrane {membrane!r} has no atoms (once waters are removed)")

        # Frames between the trajectory's frames (refinement level 0: the frames as they are).
        self.refinement = vtkMesoTrajectoryRefinement()
        self.refinement.SetInputConnection(self.membrane.GetOutputPort())
        self.refinement.SetRefinementLevels(0)
        self.refinement_level = 0
        self.mapping = vtkMesoMembraneMapping()
        self.mapping.SetSurfaceConnection(self.surface.GetOutputPort())
        self.mapping.SetMembraneConnection(self._patch_port())
        self.mapping.SetMembraneToMeshScale(self.scale)
        self.mapping.SetLatticeEdge(CUT_STRUCTURE_EDGE * self.scale)  # the cutaway's structure
        self._mapping_errors = _ErrorCatcher(self.mapping)

        self.atoms = vtkMesoAtomMapper()
        self.atoms.SetRadiusScale(self.scale)
        self.atom_actor = vtkActor()
        self.atom_actor.SetMapper(self.atoms)
        # Smooth normals for Phong shading (the meshes are coarse next to the atoms).
        self.normals = vtkPolyDataNormals()
        self.normals.SetInputConnection(self.surface.GetOutputPort())
        self.normals.SplittingOff()
        self.normals.ConsistencyOn()
        surface_mapper = vtkPolyDataMapper()
        surface_mapper.SetInputConnection(self.normals.GetOutputPort())
        surface_mapper.ScalarVisibilityOff()
        self.surface_actor = vtkActor()
        self.surface_actor.SetMapper(surface_mapper)
        surface_property = self.surface_actor.GetProperty()
        surface_property.SetInterpolationToPhong()
        surface_property.SetColor(0.78, 0.74, 0.68)
        surface_property.SetSpecular(0.3)
        surface_property.SetSpecularPower(30)
        self.renderer = vtkRenderer()
        self.renderer.SetBackground(0.09, 0.10, 0.13)
        # A patch of a few nm on a cell of tens of µm: the near plane may sit at 1e-4 of the
        # far one (VTK's default, 1e-3, would clip a close-up of a large cell away).
        self.renderer.SetNearClippingPlaneTolerance(1e-4)
        self.renderer.AddActor(self.surface_actor)
        self.renderer.AddActor(self.atom_actor)
        # The lens outlined on the cell: the boundary of the mapped disk, lifted off the surface
        # along its normals. Shown once a patch is placed.
        edges = vtkFeatureEdges()
        edges.SetInputConnection(self.mapping.GetOutputPort(1))
        edges.BoundaryEdgesOn()
        edges.FeatureEdgesOff()
        edges.NonManifoldEdgesOff()
        edges.ManifoldEdgesOff()
        lift = vtkWarpVector()
        lift.SetInputConnection(edges.GetOutputPort())
        lift.SetInputArrayToProcess(0, 0, 0, 0, "Normals")
        lift.SetScaleFactor(OUTLINE_LIFT * self.scale)
        outline_mapper = vtkPolyDataMapper()
        outline_mapper.SetInputConnection(lift.GetOutputPort())
        outline_mapper.ScalarVisibilityOff()
        self.outline_actor = vtkActor()
        self.outline_actor.SetMapper(outline_mapper)
        outline_property = self.outline_actor.GetProperty()
        outline_property.SetColor(1.0, 0.78, 0.2)
        outline_property.SetLineWidth(3)
        outline_property.LightingOff()
        self.outline_actor.VisibilityOff()
        self.renderer.AddActor(self.outline_actor)
        # The structured cutaway, off until set_cutaway(True): the mapped atoms (each tile's
        # molecules its own) against a lattice on the lens' disk; the mapper draws what stays.
        # The mapping keeps its atoms' MoleculeId and ResidueName arrays over the frames, so the
        # cutaway keeps its assignment and removal order.
        self.cutaway = vtkMesoStructuredCutaway()
        self.cutaway.SetInputConnection(self.mapping.GetOutputPort(0))
        self.cut_structure = None  # made by place(): it stays over the frames of a trajectory
        self.cutaway.MakeAssemblyWholeOff()  # mapped atoms lie on the surface, not in a box
        # The filter cuts where the plane's function is <= 0, behind its normal; ours points
        # into the cut, so the filter's plane has the opposite normal.
        self._cut_side = vtkPlane()
        self.cutaway.SetCutFunction(self._cut_side)
        self._cutaway_errors = _ErrorCatcher(self.cutaway)
        self.cutaway_on = False
        self.on_gpu = False  # the atoms warped by the mapper (place() decides)
        self.cut_origin = None
        self.cut_normal = None
        self.method = "polynomial"
        self.style = "space-filling"
        self.centre = None
        self.ssao = False
        self.shadows = False
        # Ambient occlusion and shadows (set_effects): SSAO blurred over 32 samples, shadows
        # from a sun above the patch beside a dimmed headlight.
        self._effects = vtkMesoRenderPasses()
        self._effects.SetSSAOKernelSize(32)
        self._effects.SSAOBlurOn()
        self._effects.SunLightOn()
        self.set_tiles(3)

    def _read(self, reader, what, path):
        errors = _ErrorCatcher(reader)
        reader.Update()
        message = errors.take()
        if message:
            raise LensError(f"cannot read the {what} {path!r}: {message}")

    def _patch_port(self):
        """Where the patch's atoms come from: the reader, or the refinement of its frames."""
        if self.refinement_level > 0:
            return self.refinement.GetOutputPort()
        return self.membrane.GetOutputPort()

    def _patch_source(self):
        return self.refinement if self.refinement_level > 0 else self.membrane

    def time_steps(self):
        """The membrane's time steps (ps; with the refined frames), empty without a trajectory."""
        source = self._patch_source()
        source.UpdateInformation()
        info = source.GetOutputInformation(0)
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
        return list(info.Get(sddp.TIME_STEPS()) or []) if self.has_trajectory else []

    def set_time(self, time):
        """Shows the membrane at `time` (ps)."""
        # Asked of what the atom mapper draws, the time reaches every filter up to the reader
        # (the mapping, the cutaway), and each of them runs for the new frame. Warped on the
        # GPU, the mapper draws the patch and its warp (the mapping, or the cutaway of its
        # molecules): both are asked, so that the reader serves them the same frame.
        if self.centre is not None and self.atoms.GetNumberOfInputConnections(1) > 0:
            self.atoms.GetInputAlgorithm(1, 0).UpdateTimeStep(time)
        drawn = self.atoms.GetInputAlgorithm() if self.centre is not None else None
        (drawn or self._patch_source()).UpdateTimeStep(time)

    def set_refinement(self, level):
        """2^level - 1 frames interpolated between the trajectory's frames, level in [0, 4]
        (0: the frames as they are). Takes effect at the next place()."""
        if not 0 <= int(level) <= 4:
            raise LensError(f"refinement level must be between 0 and 4, not {level}")
        self.refinement_level = int(level)
        self.refinement.SetRefinementLevels(max(1, self.refinement_level))
        self.mapping.SetMembraneConnection(self._patch_port())

    def set_tiles(self, tiles):
        """k x k tiles of the patch, k in [1, 15]."""
        if not 1 <= int(tiles) <= 15:
            raise LensError(f"tiles must be between 1 and 15, not {tiles}")
        self.tiles = int(tiles)
        self.mapping.SetTiles(self.tiles)

    def set_method(self, method):
        """'displacement', 'instancing' or 'polynomial'."""
        if method not in METHODS:
            raise LensError(f"unknown mapping method {method!r}: use one of {', '.join(METHODS)}")
        self.method = method

    def set_style(self, style):
        """'space-filling' or 'ball-and-stick'."""
        if style not in STYLES:
            raise LensError(f"unknown style {style!r}: use one of {', '.join(STYLES)}")
        self.style = style
        self.atoms.SetStyle(STYLES[style])

    def place(self, centre):
        """Maps the patch around the surface point nearest `centre` (mesh units) with the current
        tiles and method. Raises LensError with the mapping's reason when it fails (a point off
        the surface, a disk that is no disk, ...). With the cutaway on, the mapped atoms are cut
        (a new centre moves the cut plane there, facing outward) and the structure is laid on
        the new disk; if the cutaway fails, it is turned off and LensError says why."""
        self.mapping.SetSeedPoint(*centre)
        self.mapping.SetMappingMethod(METHODS[self.method])
        # Warped on the GPU, the mapping gives the molecules' centres instead of the atoms: the
        # cutaway cuts those, and the mapper hides the molecules it hides, tile by tile.
        on_gpu = self.method != "displacement"
        self.mapping.SetOutputAtoms(not on_gpu)
        self._progress(f"mapping {self.tiles} x {self.tiles} tiles by {self.method} around "
                       f"({centre[0]:.4g}, {centre[1]:.4g}, {centre[2]:.4g})")
        ok = self.mapping.GetExecutive().Update()
        message = self._mapping_errors.take()
        if not ok or message:
            self.atom_actor.VisibilityOff()
            self.outline_actor.VisibilityOff()
            raise LensError(f"the membrane cannot be mapped there: {message or 'no reason given'}")
        moved = self.centre is None or tuple(centre) != self.centre
        self.centre = tuple(centre)
        self.atom_actor.VisibilityOn()
        self.outline_actor.VisibilityOn()
        if self.mapping_note():
            self._progress(self.mapping_note())
        if on_gpu and self.cut_to_disk():
            # One tile cut to the disk: its molecules that leave the disk are dropped, which
            # only the mapped atoms show (the GPU warp would draw the whole patch).
            on_gpu = False
            self.mapping.SetOutputAtoms(True)
            self.mapping.Update()
        self.on_gpu = on_gpu
        if self.cutaway_on:
            if moved or self.cut_normal is None:
                self.set_cut_plane(self.centre, self.seed_normal())
            # A copy: the lattice stays over the frames, and so does the cutaway's assignment.
            self.cut_structure = vtkPolyData()
            self.cut_structure.ShallowCopy(self.mapping.GetOutput(2))
            self.cutaway.SetInputData(1, self.cut_structure)
            try:
                self._draw_cutaway()
                return
            except LensError:
                self.cutaway_on = False  # the whole patch rather than nothing
                self.place(centre)
                raise
        if on_gpu:
            self.atoms.SetInputConnection(self._patch_port())
            self.atoms.SetWarpConnection(self.mapping.GetOutputPort())
        else:
            self.atoms.SetInputConnection(self.mapping.GetOutputPort())
            self.atoms.SetWarpConnection(None)

    def _draw_cutaway(self):
        """Runs the cutaway on the mapped atoms, or on the molecules' centres for a warp on the
        GPU, and gives it to the mapper, which hides the atoms (molecules of a tile) whose
        `Visible` is 0: a new fraction uploads that mask, not the positions. Raises LensError
        with the cutaway's reason when it fails."""
        port = self.cutaway.GetOutputPort()
        self.cutaway.Update()
        message = self._cutaway_errors.take()
        if message or self.cutaway.GetOutput().GetNumberOfPoints() == 0:
            raise LensError(f"the membrane cannot be cut open there: {message or 'no atoms'}")
        if self.on_gpu:
            # The cut molecules' centres carry the warp and the mask; the mapper warps the patch.
            self.atoms.SetInputConnection(self._patch_port())
            self.atoms.SetWarpConnection(port)
        else:
            self.atoms.SetInputConnection(port)
            self.atoms.SetWarpConnection(None)

    def seed_normal(self):
        """The surface's unit normal at the mapped patch's centre, where the patch's +z goes (the
        mapping's SeedNormal); None before place()."""
        array = self.mapping.GetOutput().GetFieldData().GetArray(array_names.SeedNormal)
        if self.centre is None or array is None or array.GetNumberOfTuples() == 0:
            return None
        return tuple(array.GetTuple3(0))

    # The structured cutaway ----------------------------------------------------------------

    def set_cutaway(self, on):
        """Cuts the mapped membrane open (on) or shows it whole (off). The cut is the half-space
        of set_cut_plane, at first the plane through the lens' centre facing along the surface's
        normal there (seed_normal: the side of the patch's upper leaflet); of the molecules there, set_cut_fraction's share is hidden (default
        0.5), in structured order (a wireframe of triangles of CUT_STRUCTURE_EDGE Å; patches with
        set_cut_inverted) or random order (set_cut_random). The polynomial and instancing methods
        stay on the GPU: the molecules' centres are cut, and the mapper hides the molecules of
        each tile that the cutaway hides. Raises LensError before place() or when the cutaway fails (it is then off)."""
        on = bool(on)
        if on and self.centre is None:
            raise LensError("place the membrane first: the cutaway cuts the mapped membrane open")
        if on == self.cutaway_on:
            return
        self.cutaway_on = on
        if self.centre is not None:
            self.place(self.centre)

    def set_cut_plane(self, origin, normal):
        """The cut: the half-space in front of the plane through `origin` (mesh units) that
        `normal` (any length but 0) points into. Raises LensError for non-finite numbers or a
        zero normal."""
        try:
            origin = tuple(float(v) for v in origin)
            normal = tuple(float(v) for v in normal)
        except (TypeError, ValueError):
            raise LensError(f"the cut plane needs an origin and a normal of 3 numbers each, not "
                            f"{origin!r} and {normal!r}") from None
        if len(origin) != 3 or len(normal) != 3 or not all(map(math.isfinite, origin + normal)):
            raise LensError(f"the cut plane needs an origin and a normal of 3 finite numbers "
                            f"each, not {origin} and {normal}")
        length = math.sqrt(sum(v * v for v in normal))
        if length == 0:
            raise LensError("the cut plane's normal must not be zero")
        self.cut_origin = origin
        self.cut_normal = tuple(v / length for v in normal)
        self._cut_side.SetOrigin(*origin)
        self._cut_side.SetNormal(*(-v for v in self.cut_normal))

    def set_cut_fraction(self, fraction):
        """Hide this share of the molecules in the cut, in [0, 1] (0: none, 1: all); 0.5 at
        first. Raises LensError outside [0, 1] (the cutaway keeps its fraction)."""
        try:
            value = float(fraction)
        except (TypeError, ValueError):
            value = math.nan
        if not 0.0 <= value <= 1.0:
            raise LensError(f"the fraction hidden must be between 0 and 1 (0 % and 100 %), "
                            f"not {fraction!r}")
        self.cutaway.SetFractionHidden(value)

    @property
    def cut_fraction(self):
        """The share of the molecules in the cut that is hidden, [0, 1]."""
        return self.cutaway.GetFractionHidden()

    def set_cut_inverted(self, inverted):
        """Hide the molecules on the structure's edges first (patches stay) instead of those at
        the triangles' centres (a wireframe stays). No effect in random order."""
        self.cutaway.SetInverted(bool(inverted))

    @property
    def cut_inverted(self):
        return bool(self.cutaway.GetInverted())

    def set_cut_random(self, random):
        """Hide molecules in a random (seeded, stable) order instead of the structured one: the
        Visibility Equalizer's removal, for comparison."""
        self.cutaway.SetRandomOrder(bool(random))

    @property
    def cut_random(self):
        return bool(self.cutaway.GetRandomOrder())

    def cut_counts(self):
        """(molecules hidden, molecules in the cut), or None while the cutaway is off or has
        nothing to show."""
        if not self.cutaway_on:
            return None
        self.cutaway.Update()
        self._cutaway_errors.take()  # place() reports failures; here only the numbers count
        fields = self.cutaway.GetOutput().GetFieldData()
        hidden = fields.GetArray(array_names.MoleculesHidden)
        in_cut = fields.GetArray(array_names.MoleculesInCut)
        if hidden is None or in_cut is None:
            return None
        return int(hidden.GetValue(0)), int(in_cut.GetValue(0))

    def set_effects(self, ssao=False, shadows=False):
        """Ambient occlusion (SSAO, sized to the patch) and shadows (from a sun above the patch,
        beside the headlight) on or off, through a vtkMesoRenderPasses. Both need the renderer
        to start at the window's origin (VTK 9.1's SSAO pass draws black elsewhere)."""
        self.ssao = bool(ssao)
        self.shadows = bool(shadows)
        extent, centre, outward = self._patch_frame()
        self._effects.SetSSAO(self.ssao)
        self._effects.SetSSAORadius(0.05 * extent)
        self._effects.SetSSAOBias(0.005 * extent)
        self._effects.SetShadows(self.shadows)
        self._effects.SetSunFocalPoint(centre)
        self._effects.SetSunPosition([centre[d] + 4 * extent * outward[d] for d in range(3)])
        self._effects.Apply(self.renderer)

    def _patch_frame(self):
        """The patch's size, centre and outward direction (or the surface's, before place())."""
        source = self.atoms if self.centre is not None else self.surface.GetOutput()
        bounds = source.GetBounds()
        centre = [(bounds[2 * d] + bounds[2 * d + 1]) / 2 for d in range(3)]
        organelle = self.surface.GetOutput().GetCenter()
        outward = [centre[d] - organelle[d] for d in range(3)]
        length = sum(v * v for v in outward) ** 0.5 or 1.0
        extent = max(bounds[2 * d + 1] - bounds[2 * d] for d in range(3))
        if self.centre is None:
            extent *= 0.05
        return extent, centre, [v / length for v in outward]

    def _mapping_field(self, name):
        array = self.mapping.GetOutput().GetFieldData().GetAbstractArray(name)
        return array.GetValue(0) if array is not None and array.GetNumberOfValues() else None

    def tiles_mapped(self):
        """k of the k x k tiles mapped (fewer than asked where they do not fit), 0 before
        place()."""
        value = self._mapping_field(array_names.TilesMapped) if self.centre is not None else None
        return int(value) if value is not None else 0

    def cut_to_disk(self):
        """Whether the mapping cut its one tile to the disk (not even one tile fitted)."""
        value = self._mapping_field(array_names.CutToDisk) if self.centre is not None else None
        return bool(value)

    def mapping_note(self):
        """What was mapped instead of what was asked, and why; '' when the request was met."""
        value = self._mapping_field(array_names.MappingNote) if self.centre is not None else None
        return value or ""

    def atom_count(self):
        """Atoms drawn: the mapped atoms (the patch's times the tiles mapped on the GPU), or
        those the cutaway leaves."""
        if self.centre is None:
            return 0
        if self.cutaway_on:
            self.cutaway.Update()
            self._cutaway_errors.take()
            visible = self.cutaway.GetOutput().GetPointData().GetArray(array_names.Visible)
            if visible is None:
                return 0
            visible = vtk_to_numpy(visible)
            if not self.on_gpu:
                return int(np.count_nonzero(visible))
            # A visible flag per molecule and tile: times the molecules' atoms.
            ids = vtk_to_numpy(self._patch_source().GetOutput().GetPointData()
                               .GetArray(array_names.MoleculeId))
            _, first, sizes = np.unique(ids, return_index=True, return_counts=True)
            sizes = sizes[np.argsort(first)]  # in order of first appearance
            tiles = visible.size // sizes.size
            return int(np.sum(visible.reshape(tiles, sizes.size) != 0, axis=0) @ sizes)
        if not self.on_gpu:
            return self.mapping.GetOutput().GetNumberOfPoints()
        return self.membrane.GetOutput().GetNumberOfPoints() * self.tiles_mapped() ** 2

    def _seed_normal(self):
        """The surface's outward normal under the mapped patch (the disk's mean normal), or None."""
        normals = self.mapping.GetOutput(1).GetPointData().GetNormals()
        if normals is None or normals.GetNumberOfTuples() == 0:
            return None
        mean = vtk_to_numpy(normals).mean(axis=0)
        length = float(np.linalg.norm(mean))
        return [float(v) / length for v in mean] if length > 0 else None

    def patch_pixels(self, window, renderer=None):
        """How many pixels of `renderer`'s viewport (default: the lens's) the mapped atoms
        change: rendered once without them and once with them (0 when they are out of view or
        hidden behind the surface)."""
        renderer = renderer or self.renderer
        from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

        def grab():
            window.Render()
            grabber = vtkWindowToImageFilter()
            grabber.SetInput(window)
            grabber.ReadFrontBufferOff()
            grabber.Update()
            image = grabber.GetOutput()
            width, height, _ = image.GetDimensions()
            pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
            x0, y0, x1, y1 = renderer.GetViewport()
            return pixels[int(y0 * height):int(y1 * height), int(x0 * width):int(x1 * width)]

        shown = self.atom_actor.GetVisibility()
        self.atom_actor.VisibilityOff()
        without = grab()
        self.atom_actor.VisibilityOn()
        with_atoms = grab()
        self.atom_actor.SetVisibility(shown)
        return int(np.count_nonzero(np.any(without != with_atoms, axis=-1)))

    def patch_geometry(self):
        """The mapped patch's centre (of its atoms' bounds), outward direction (the disk's mean
        normal; before place(), away from the organelle's centre) and extent (the largest side of
        its atoms' bounds), in world units."""
        bounds = self.atoms.GetBounds()
        centre = [(bounds[2 * d] + bounds[2 * d + 1]) / 2 for d in range(3)]
        outward = self._seed_normal()
        if outward is None:
            organelle = self.surface.GetOutput().GetCenter()
            outward = [centre[d] - organelle[d] for d in range(3)]
        length = sum(v * v for v in outward) ** 0.5 or 1.0
        extent = max(bounds[2 * d + 1] - bounds[2 * d] for d in range(3))
        return centre, [v / length for v in outward], extent

    def scale_poses(self, current, aspect=1.0):
        """The camera poses (mesolens.camera.CameraPose) of the two scales for the placed patch:
        the patch close up (filling the window, at a slant that shows the bilayer's thickness)
        and the whole surface seen from the patch's side; with the up and view angle of the
        `current` pose, for a window of `aspect` (width / height)."""
        centre, outward, extent = self.patch_geometry()
        surface = self.surface.GetOutput()
        return (patch_pose(centre, outward, extent, current, aspect),
                whole_pose(surface.GetBounds(), surface.GetCenter(), outward, current, aspect))

    def look_at_patch(self, renderer=None, distance_factor=3.0, elevation=25.0):
        """Points the camera of `renderer` (default: the lens's) at the mapped patch from
        outside the surface (along its normal there), the patch filling about 1/distance_factor
        of the view."""
        renderer = renderer or self.renderer
        centre, outward, extent = self.patch_geometry()
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(centre)
        camera.SetPosition([centre[d] + distance_factor * extent * outward[d] for d in range(3)])
        camera.SetViewUp(0, 0, 1)
        camera.OrthogonalizeViewUp()
        camera.Elevation(elevation)
        camera.OrthogonalizeViewUp()
        renderer.ResetCameraClippingRange()

    def whole_view(self):
        """A second renderer that shows the whole surface with the patch (the same actors),
        seen from the patch's side."""
        renderer = vtkRenderer()
        renderer.SetBackground(*self.renderer.GetBackground())
        renderer.AddActor(self.surface_actor)
        renderer.AddActor(self.atom_actor)
        renderer.AddActor(self.outline_actor)
        self.look_at_patch(renderer, distance_factor=1.0, elevation=0.0)
        camera = renderer.GetActiveCamera()
        bounds = self.surface.GetOutput().GetBounds()
        organelle = self.surface.GetOutput().GetCenter()
        direction = [camera.GetPosition()[d] - camera.GetFocalPoint()[d] for d in range(3)]
        length = sum(v * v for v in direction) ** 0.5 or 1.0
        diagonal = sum((bounds[2 * d + 1] - bounds[2 * d]) ** 2 for d in range(3)) ** 0.5
        camera.SetFocalPoint(organelle)
        camera.SetPosition([organelle[d] + 1.6 * diagonal * direction[d] / length
                            for d in range(3)])
        renderer.ResetCameraClippingRange()
        return renderer
