# SPDX-License-Identifier: GPL-3.0-or-later
"""The MesoLens scene: a cell surface with a membrane patch mapped onto it around a point.

``MembraneLens`` reads a cell-component mesh and a membrane patch (a structure or topology file,
optionally with a trajectory), maps the patch onto the surface around a centre point with
``vtkMesoMembraneMapping`` and draws both: the surface Phong-shaded, the atoms through
``vtkMesoAtomMapper`` (warped on the GPU for the polynomial and instancing methods, mapped on the
CPU for displacement). The ``mesolens`` command is built on it.

Units: the mesh in ``mesh_unit_angstrom`` Å per unit (1e4 for µm, the default; 10 for nm); the
membrane in Å (GROMACS files are converted by the reader).
"""
import math
import os

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

from .MesoLensFilters import (vtkMesoMembraneMapping, vtkMesoMeshReader,
                              vtkMesoStructureReader, vtkMesoTrajectoryReader,
                              vtkMesoTrajectoryRefinement)
from .MesoLensRendering import vtkMesoAtomMapper

METHODS = {"displacement": vtkMesoMembraneMapping.DISPLACEMENT,
           "instancing": vtkMesoMembraneMapping.MOLECULE_INSTANCING,
           "polynomial": vtkMesoMembraneMapping.POLYNOMIAL}
STYLES = {"space-filling": vtkMesoAtomMapper.SPACE_FILLING,
          "ball-and-stick": vtkMesoAtomMapper.BALL_AND_STICK}
TRAJECTORY_SUFFIXES = (".xtc", ".trr")


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
        self.renderer.AddActor(self.surface_actor)
        self.renderer.AddActor(self.atom_actor)
        self.method = "polynomial"
        self.style = "space-filling"
        self.centre = None
        self.ssao = False
        self.shadows = False
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
        self._patch_source().UpdateTimeStep(time)

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
        the surface, a disk that is no disk, ...)."""
        self.mapping.SetSeedPoint(*centre)
        self.mapping.SetMappingMethod(METHODS[self.method])
        on_gpu = self.method != "displacement"
        self.mapping.SetOutputAtoms(not on_gpu)
        self._progress(f"mapping {self.tiles} x {self.tiles} tiles by {self.method} around "
                       f"({centre[0]:.4g}, {centre[1]:.4g}, {centre[2]:.4g})")
        ok = self.mapping.GetExecutive().Update()
        message = self._mapping_errors.take()
        if not ok or message:
            self.atom_actor.VisibilityOff()
            raise LensError(f"the membrane cannot be mapped there: {message or 'no reason given'}")
        if on_gpu:
            self.atoms.SetInputConnection(self._patch_port())
            self.atoms.SetWarpConnection(self.mapping.GetOutputPort())
        else:
            self.atoms.SetInputConnection(self.mapping.GetOutputPort())
            self.atoms.SetWarpConnection(None)
        self.atom_actor.VisibilityOn()
        self.centre = tuple(centre)

    def set_effects(self, ssao=False, shadows=False):
        """Ambient occlusion (vtkSSAOPass, sized to the patch) and shadows (vtkShadowMapPass,
        from a light above the patch, beside the headlight) on or off. Both need the renderer
        to start at the window's origin (VTK 9.1's SSAO pass draws black elsewhere)."""
        from vtkmodules.vtkRenderingCore import vtkLight
        from vtkmodules.vtkRenderingOpenGL2 import (vtkCameraPass, vtkRenderPassCollection,
                                                    vtkRenderStepsPass, vtkSequencePass,
                                                    vtkShadowMapPass, vtkSSAOPass)
        self.ssao = bool(ssao)
        self.shadows = bool(shadows)
        self.renderer.RemoveAllLights()  # back to VTK's headlight
        extent, centre, outward = self._patch_frame()
        keep = []
        if self.shadows:
            headlight = vtkLight()
            headlight.SetLightTypeToHeadlight()
            headlight.SetIntensity(0.5)
            sun = vtkLight()
            sun.SetLightTypeToSceneLight()
            sun.SetFocalPoint(centre)
            sun.SetPosition([centre[d] + 4 * extent * outward[d] for d in range(3)])
            sun.PositionalOn()
            sun.SetConeAngle(45)
            sun.SetIntensity(0.7)
            self.renderer.AddLight(headlight)
            self.renderer.AddLight(sun)
            shadow = vtkShadowMapPass()
            passes = vtkRenderPassCollection()
            passes.AddItem(shadow.GetShadowMapBakerPass())
            passes.AddItem(shadow)
            sequence = vtkSequencePass()
            sequence.SetPasses(passes)
            base = vtkCameraPass()
            base.SetDelegatePass(sequence)
            keep += [headlight, sun, shadow, passes, sequence]
        else:
            base = vtkRenderStepsPass()
        top = base if self.shadows else None
        if self.ssao:
            occlusion = vtkSSAOPass()
            occlusion.SetDelegatePass(base)
            occlusion.SetRadius(0.05 * extent)
            occlusion.SetBias(0.005 * extent)
            occlusion.SetKernelSize(32)
            occlusion.BlurOn()
            top = occlusion
        self._effects = keep + [base, top]  # VTK holds passes weakly from Python's side
        self.renderer.SetPass(top)

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

    def atom_count(self):
        """Atoms drawn: the patch's atoms times the tiles."""
        return self.membrane.GetOutput().GetNumberOfPoints() * self.tiles * self.tiles

    def look_at_patch(self, renderer=None, distance_factor=3.0, elevation=25.0):
        """Points the camera of `renderer` (default: the lens's) at the mapped patch from
        outside the surface, the patch filling about 1/distance_factor of the view."""
        renderer = renderer or self.renderer
        bounds = self.atoms.GetBounds()
        centre = [(bounds[2 * d] + bounds[2 * d + 1]) / 2 for d in range(3)]
        organelle = self.surface.GetOutput().GetCenter()
        outward = [centre[d] - organelle[d] for d in range(3)]
        length = sum(v * v for v in outward) ** 0.5 or 1.0
        extent = max(bounds[2 * d + 1] - bounds[2 * d] for d in range(3))
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(centre)
        camera.SetPosition([centre[d] + distance_factor * extent * outward[d] / length
                            for d in range(3)])
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
