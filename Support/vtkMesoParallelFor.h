// SPDX-License-Identifier: GPL-3.0-or-later
// The ParallelFor that MesoLens's VTK modules hand to Core: vtkSMPTools::For, so Core's loops
// use VTK's threading backend and its thread count (private to the MesoLens modules; inline so
// that the rendering module uses it without an exported symbol).
#ifndef vtkMesoParallelFor_h
#define vtkMesoParallelFor_h

#include "mesolens/common/parallel_for.h"

#include <vtkSMPTools.h>

#include <cstdlib>
#include <string>
#include <utility>

namespace vtkMesoParallelFor {
/// Makes VTK's SMP tools use threads. ParaView 5.11's VTK starts on its Sequential backend (one
/// thread) unless VTK_SMP_BACKEND_IN_USE names one; when that variable is unset and the backend
/// is Sequential, this switches to STDThread (all cores, or VTK_SMP_MAX_THREADS). Once per
/// process; a backend the user chose is kept.
inline void UseThreads()
{
  static const bool chosen = [] {
    if (!std::getenv("VTK_SMP_BACKEND_IN_USE") &&
        std::string(vtkSMPTools::GetBackend()) == "Sequential")
    {
      vtkSMPTools::SetBackend("STDThread");
    }
    return true;
  }();
  (void)chosen;
}

/// The number of threads VTK's SMP tools run on (after UseThreads).
inline int ThreadCount()
{
  UseThreads();
  return vtkSMPTools::GetEstimatedNumberOfThreads();
}

/// vtkSMPTools::For over [begin, end), on threads (UseThreads).
template<typename Functor>
inline void For(vtkIdType begin, vtkIdType end, Functor&& functor)
{
  UseThreads();
  vtkSMPTools::For(begin, end, std::forward<Functor>(functor));
}

/// A mesolens::ParallelFor running its ranges through vtkSMPTools::For (on threads).
inline mesolens::ParallelFor Get()
{
  UseThreads();
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&kernel](vtkIdType begin, vtkIdType end) {
      kernel(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    });
  };
}
}

#endif
