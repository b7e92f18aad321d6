// SPDX-License-Identifier: GPL-3.0-or-later
// The Core reading parameters that a vtkMesoAtomReader's options stand for (private to
// MesoLensFilters: public VTK headers do not expose Core types).
#ifndef vtkMesoAtomReaderParameters_h
#define vtkMesoAtomReaderParameters_h

#include "mesolens/io/structure_file.h"

class vtkMesoAtomReader;

/// Water removal, bond perception and coarse-grained options of `reader`, with VTK's SMP
/// backend for the parallel loops.
mesolens::StructureReadParams vtkMesoAtomReaderParameters(vtkMesoAtomReader* reader);

#endif
