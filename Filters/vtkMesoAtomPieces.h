// SPDX-License-Identifier: GPL-3.0-or-later
// Atoms on many processes (pvbatch or pvserver on MPI ranks): which molecules make a piece, and
// subsets of atoms with their bonds (private to MesoLensFilters; not installed, not wrapped).
#ifndef vtkMesoAtomPieces_h
#define vtkMesoAtomPieces_h

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <initializer_list>
#include <utility>
#include <vector>

class vtkInformation;
class vtkInformationVector;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vtkMesoAtomPieces {

/// The piece an update asks of an output, (piece, pieces): (0, 1) when it asks for none.
std::pair<int, int> Requested(vtkInformation* output_information);

/// The atoms (ascending ids) of piece `piece` of `pieces` of MesoLens atoms: whole molecules
/// (`MoleculeId`; each atom its own without it), each in the piece where its first atom falls
/// when the atoms are cut into `pieces` runs of equal counts. The same atoms give the same
/// pieces whichever reader or filter cuts them. 0 <= piece < pieces.
std::vector<vtkIdType> AtomsOfPiece(vtkPolyData* atoms, int piece, int pieces);

/// Keeps only the atoms of AtomsOfPiece, with their bonds, in place (nothing changes for one
/// piece).
void KeepPiece(vtkPolyData* atoms, int piece, int pieces);

/// The atoms `ids` (ascending) of `atoms` with their bonds, as ExtractAtoms gives them, into
/// `output` (which may be `atoms` itself).
void ExtractAtomIds(vtkPolyData* atoms, const std::vector<vtkIdType>& ids, vtkPolyData* output);

/// Whether an update that asks `output_information` for a piece gathers its inputs' pieces
/// from the other processes: N pieces asked on N MPI processes (ParaView's pvbatch, pvserver).
bool Gathers(vtkInformation* output_information);

/// For filters that need whole inputs (with GatheredInput): when one process is asked for a
/// piece of several (VTK's streaming), asks the inputs on ports [0, ports) for all of their
/// data; on N processes the inputs keep their pieces and GatheredInput collects them.
void RequestWholeInputsWhenStreaming(vtkInformationVector** inputs, int ports,
                                     vtkInformationVector* outputs);

/// Every process's data of one input, for filters that need all of it (secondary structure
/// across chains, surfaces of touching molecules, the membrane mapping's surface and patch)
/// while every process keeps asking its readers for its own piece (so a reader shown and
/// filtered at once is not read twice).
///
/// On N processes (ParaView's pvbatch or pvserver on MPI ranks; the update asks for one of N
/// pieces and the global controller has N processes) the constructor gathers every process's
/// polydata of `input`, appended in rank order with the field data of the first that has
/// points: a collective call, so every process must construct it at the same point of its
/// update. Alone, Whole() is the input itself (whole, when streaming, by
/// RequestWholeInputsWhenStreaming). With KeepOwn, the destructor reduces output 0 of
/// `outputs`, computed from Whole() with one point per atom in the same order, to this
/// process's own atoms (streaming: to the piece asked for, KeepPiece), on every return path.
/// `only_arrays` (KeepWhole only): gather the points, these point arrays and the field data, no
/// cells and no other array, for filters that read little of many atoms; empty: everything.
class GatheredInput
{
public:
  enum Output
  {
    KeepOwn,  ///< output 0 is per atom: keep this process's atoms of it
    KeepWhole ///< output 0 is something else (or left as it is)
  };
  GatheredInput(vtkInformationVector* input, vtkInformationVector* outputs, Output output,
                std::initializer_list<const char*> only_arrays = {});
  ~GatheredInput();
  GatheredInput(const GatheredInput&) = delete;
  GatheredInput& operator=(const GatheredInput&) = delete;

  /// Every process's data (or the input alone); may be empty, never null.
  vtkPolyData* Whole() const;
  /// Whether other processes' data were gathered.
  bool Gathered() const;
  /// The piece this update makes: the process's rank when gathered, the piece asked for when
  /// streaming, 0 alone. Outputs that are not split (a surface of every atom) are piece 0's.
  int Piece() const;
  /// The pieces of this update (1 alone).
  int PieceCount() const;
  /// Where this process's own atoms start in Whole() (0 alone).
  vtkIdType FirstOwn() const;
  /// Changes when any process's input changes (the sum of their modification times; alone, the
  /// input's): a key for work kept while the whole input stays.
  vtkMTimeType Version() const;

private:
  vtkInformationVector* Outputs;
  Output Keep;
  vtkSmartPointer<vtkPolyData> All;
  vtkIdType First = 0; // where this process's atoms start in All
  vtkIdType Own = 0;   // and how many
  int ThisPiece = 0;
  int Pieces = 1;
  bool WasGathered = false;
  vtkMTimeType Versions = 0;
};

/// The atoms whose `keep` is non-zero, with their point data, and the vertices and bonds whose
/// atoms are all kept, with their cell data; field data as they are.
void ExtractAtoms(vtkPolyData* atoms, const vtkUnsignedCharArray* keep, vtkPolyData* output);

} // namespace vtkMesoAtomPieces

#endif
