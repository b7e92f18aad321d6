// SPDX-License-Identifier: GPL-3.0-or-later
// The ParallelFor that MesoLens's VTK modules hand to Core: vtkSMPTools::For, so Core's loops
// use VTK's threading backend and its thread count (private to the MesoLens modules; inline so
// that the rendering module uses it without an exported symbol).
#ifndef vtkMesoParallelFor_h
#define vtkMesoParallelFor_h

#include "mesolens/common/parallel_for.h"

#include <vtkSMPTools.h>

namespace vtkMesoParallelFor {
/// A mesolens::ParallelFor running its ranges through vtkSMPTools::For.
inline mesolens::ParallelFor Get()
{
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&kernel](vtkIdType begin, vtkIdType end) {
      kernel(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    });
  };
}
}

#endif
