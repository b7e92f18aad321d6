// SPDX-License-Identifier: GPL-3.0-or-later
// Atoms on many processes (pvbatch or pvserver on MPI ranks): which molecules make a piece, and
// subsets of atoms with their bonds (private to MesoLensFilters; not installed, not wrapped).
#ifndef vtkMesoAtomPieces_h
#define vtkMesoAtomPieces_h

#include <vtkType.h>

#include <utility>
#include <vector>

class vtkInformation;
class vtkInformationVector;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vtkMesoAtomPieces {

/// The piece an update asks of an output, (piece, pieces): (0, 1) when it asks for none.
std::pair<int, int> Requested(vtkInformation* output_information);

/// Asks the inputs on ports [0, ports) for their whole data (piece 0 of 1): for filters that
/// need every atom (secondary structure across chains, surfaces of touching molecules).
void RequestWholeInputs(vtkInformationVector** inputs, int ports);

/// The atoms (ascending ids) of piece `piece` of `pieces` of MesoLens atoms: whole molecules
/// (`MoleculeId`; each atom its own without it), each in the piece where its first atom falls
/// when the atoms are cut into `pieces` runs of equal counts. The same atoms give the same
/// pieces whichever reader or filter cuts them. 0 <= piece < pieces.
std::vector<vtkIdType> AtomsOfPiece(vtkPolyData* atoms, int piece, int pieces);

/// Keeps only the atoms of AtomsOfPiece, with their bonds, in place (nothing changes for one
/// piece).
void KeepPiece(vtkPolyData* atoms, int piece, int pieces);

/// For filters that compute on every atom and keep atoms (secondary structure, surface area):
/// when it goes out of scope, keeps the piece the update asked of output port 0 of
/// `outputs` (KeepPiece), on every return path.
class PieceOnReturn
{
public:
  explicit PieceOnReturn(vtkInformationVector* outputs);
  ~PieceOnReturn();
  PieceOnReturn(const PieceOnReturn&) = delete;
  PieceOnReturn& operator=(const PieceOnReturn&) = delete;

private:
  vtkInformationVector* Outputs;
};

/// The atoms whose `keep` is non-zero, with their point data, and the vertices and bonds whose
/// atoms are all kept, with their cell data; field data as they are.
void ExtractAtoms(vtkPolyData* atoms, const vtkUnsignedCharArray* keep, vtkPolyData* output);

} // namespace vtkMesoAtomPieces

#endif
