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
#include <thread>
#include <utility>
#include <vector>

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

/// MESOLENS_THREADS, when set to a count >= 1: MesoLens' loops then run on that many threads
/// of their own (the range split evenly) instead of VTK's SMP tools, whose STDThread backend
/// takes no more threads than there are cores. For checking that results do not depend on the
/// thread count. 0 when unset.
inline int OwnThreads()
{
  const char* value = std::getenv("MESOLENS_THREADS");
  const int count = value ? std::atoi(value) : 0;
  return count > 0 ? count : 0;
}

/// Runs functor(b, e) over `threads` even parts of [begin, end), the last on this thread.
template<typename Functor>
inline void ForOnOwnThreads(vtkIdType begin, vtkIdType end, int threads, Functor& functor)
{
  const vtkIdType count = end - begin;
  const auto part = [&](int t) { return begin + count * t / threads; };
  std::vector<std::thread> others;
  for (int t = 0; t + 1 < threads; ++t)
  {
    others.emplace_back([&, t] {
      if (part(t) < part(t + 1))
      {
        functor(part(t), part(t + 1));
      }
    });
  }
  if (part(threads - 1) < end)
  {
    functor(part(threads - 1), end);
  }
  for (std::thread& other : others)
  {
    other.join();
  }
}

/// The number of threads MesoLens' loops run on (after UseThreads).
inline int ThreadCount()
{
  UseThreads();
  return OwnThreads() > 0 ? OwnThreads() : vtkSMPTools::GetEstimatedNumberOfThreads();
}

/// vtkSMPTools::For over [begin, end), on threads (UseThreads; MESOLENS_THREADS, see OwnThreads).
template<typename Functor>
inline void For(vtkIdType begin, vtkIdType end, Functor&& functor)
{
  UseThreads();
  if (const int threads = OwnThreads())
  {
    ForOnOwnThreads(begin, end, threads, functor);
    return;
  }
  vtkSMPTools::For(begin, end, std::forward<Functor>(functor));
}

/// A mesolens::ParallelFor running its ranges through vtkSMPTools::For (on threads;
/// MESOLENS_THREADS, see OwnThreads).
inline mesolens::ParallelFor Get()
{
  UseThreads();
  if (const int threads = OwnThreads())
  {
    return [threads](std::size_t count, const mesolens::RangeKernel& kernel) {
      const auto range = [&kernel](vtkIdType begin, vtkIdType end) {
        kernel(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
      };
      ForOnOwnThreads(0, static_cast<vtkIdType>(count), threads, range);
    };
  }
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&kernel](vtkIdType begin, vtkIdType end) {
      kernel(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    });
  };
}
}

#endif
