// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoParallelFor.h"

#include <vtkSMPTools.h>

namespace vtkMesoParallelFor {

mesolens::ParallelFor Get()
{
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&kernel](vtkIdType begin, vtkIdType end) {
      kernel(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    });
  };
}

}
