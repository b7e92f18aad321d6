// SPDX-License-Identifier: GPL-3.0-or-later
// The ParallelFor that MesoLens filters hand to Core: vtkSMPTools::For, so Core's loops use
// VTK's threading backend and its thread count (private to MesoLensFilters).
#ifndef vtkMesoParallelFor_h
#define vtkMesoParallelFor_h

#include "mesolens/parallel_for.h"

namespace vtkMesoParallelFor {
/// A mesolens::ParallelFor running its ranges through vtkSMPTools::For.
mesolens::ParallelFor Get();
}

#endif
