// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoTrajectoryRefinement
 * @brief   Refines a trajectory in time: inserts 2^L - 1 frames between consecutive key frames
 *          by 4-point interpolatory subdivision (Membrane Mapping, Waltemate et al. 2014).
 *
 * Works on any point set whose pipeline reports TIME_STEPS (typically the vtkPolyData of
 * vtkMesoTrajectoryReader, mapped or not); the output has the input's type. With K key frames
 * (input TIME_STEPS) and L = RefinementLevels the output reports (K - 1)·2^L + 1 TIME_STEPS,
 * linear between consecutive key times (see mesolens::refined_times), and TIME_RANGE.
 *
 * A request for time t gives the refined frame whose time is the latest not after t (clamped
 * to the first/last frame). Its points are x(t + 1/2) = (-x(t-1) + 9x(t) + 9x(t+1) - x(t+2))/16
 * applied L times, evaluated directly as a fixed combination of at most 6 key frames (the
 * stencil of mesolens::subdivision_stencil; reflected linear extrapolation at the ends, so
 * linear motion is exact everywhere and cubic motion inside). Key times give the key frame
 * exactly. Only the stencil's key frames are requested from upstream, one at a time (the one
 * nearest in time first, through the normal update request; the others by updating the input
 * at their times from RequestData), so memory is O(atoms): one float copy of the points of each
 * stencil frame and one shallow copy of the nearest key frame.
 *
 * The output is that nearest key frame (cells, point/cell data and field data shallow-copied,
 * e.g. the reader's `TimePs`, `FrameIndex` and `PeriodicBoxVectors`) with the refined points
 * (float), DATA_TIME_STEP set to the refined time, and field data `RefinedFrameIndex` (one
 * double, the index in the refined TIME_STEPS).
 *
 * Periodic boundaries: with UnwrapPeriodicJumps, when a key frame carries field data
 * `PeriodicBoxVectors` (9 values, rows a, b, c, in the points' length unit), its atoms are first
 * moved by whole box vectors to the minimum image of the same atoms in the adjacent key frame
 * of the stencil on the side of the nearest one (working outwards from the nearest key frame),
 * so an atom that crosses the box between key frames moves continuously instead of flying
 * across it. With a point array `MoleculeId` (as from the MesoLens readers, whose molecules are
 * whole) each molecule moves as one, by the minimum image of its mean displacement, so whole
 * molecules stay whole; otherwise each atom moves alone (mesolens::unwrap_to_reference).
 * Chaining neighbour to neighbour only assumes that atoms move less than half a box between
 * consecutive key frames.
 *
 * Errors (an input without TIME_STEPS, key frames with different point counts, non-finite
 * coordinates, a key frame the input fails to produce) are reported with vtkErrorMacro naming
 * the key frame; the output is then empty and the update fails. (When the nearest key frame
 * itself fails, VTK reports the input's own error and the update fails before this filter
 * runs.)
 */
#ifndef vtkMesoTrajectoryRefinement_h
#define vtkMesoTrajectoryRefinement_h

#include "MesoLensFiltersModule.h"
#include "vtkPointSetAlgorithm.h"

#include <cstddef>
#include <memory>

class vtkPointSet;

class MESOLENSFILTERS_EXPORT vtkMesoTrajectoryRefinement : public vtkPointSetAlgorithm
{
public:
  static vtkMesoTrajectoryRefinement* New();
  vtkTypeMacro(vtkMesoTrajectoryRefinement, vtkPointSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Refinement levels L: 2^L - 1 frames are inserted between consecutive key frames (L = 0
  /// passes the key frames through). Range [0, 8]; default 2.
  vtkSetClampMacro(RefinementLevels, int, 0, 8);
  vtkGetMacro(RefinementLevels, int);
  ///@}

  ///@{
  /// Undo periodic-box crossings between key frames before combining them (needs field data
  /// `PeriodicBoxVectors` on the input; without it nothing is moved). Default: true.
  vtkSetMacro(UnwrapPeriodicJumps, bool);
  vtkGetMacro(UnwrapPeriodicJumps, bool);
  vtkBooleanMacro(UnwrapPeriodicJumps, bool);
  ///@}

  /// Number of refined frames, (K - 1)·2^L + 1 (valid after UpdateInformation; 0 when the input
  /// has no time steps).
  int GetNumberOfRefinedFrames();

protected:
  vtkMesoTrajectoryRefinement();
  ~vtkMesoTrajectoryRefinement() override;

  /// RequestInformation: publishes the refined TIME_STEPS and TIME_RANGE.
  int ExecuteInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestUpdateExtent: asks the input for the key frame nearest the requested refined frame.
  int ComputeInputUpdateExtent(vtkInformation*, vtkInformationVector**,
                               vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int RefinementLevels = 2;
  bool UnwrapPeriodicJumps = true;

private:
  vtkMesoTrajectoryRefinement(const vtkMesoTrajectoryRefinement&) = delete;
  void operator=(const vtkMesoTrajectoryRefinement&) = delete;

  /// The input at key time `time`: as it is when it already holds that time, else after
  /// updating the input's producer for it. Null when the update fails.
  vtkPointSet* UpdateInputTo(double time, vtkInformation* inInfo);

  /// Loads the key frames refined frame `frame` depends on (nearest first, then outwards),
  /// checks and unwraps them. False, with the error reported, when the frame cannot be refined
  /// or a key frame is missing, differs in points or is not finite.
  struct KeyFrames;
  bool LoadKeyFrames(std::size_t frame, vtkInformation* inInfo, KeyFrames& frames);

  struct State;
  std::unique_ptr<State> Internal;
};

#endif
