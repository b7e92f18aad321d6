// SPDX-License-Identifier: GPL-3.0-or-later
// Atoms on many processes: each piece (as one MPI rank asks for it) holds whole molecules, the
// pieces together hold every atom once, and what filters compute on a piece equals what they
// compute on the whole.
#include "vtkMesoArrayNames.h"
#include "vtkMesoMolecularSurface.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoSurfaceArea.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_test_data.h"

#include <vtkAlgorithm.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

using mesolens_test::data_file;

namespace {
/// Piece `piece` of `pieces` of an algorithm's output 0 (at `time` when it is a number), copied.
vtkSmartPointer<vtkPolyData> piece_of(vtkAlgorithm* algorithm, int piece, int pieces,
                                      double time = std::nan(""))
{
  EXPECT_EQ(std::isnan(time) ? algorithm->UpdatePiece(piece, pieces, 0)
                             : algorithm->UpdateTimeStep(time, piece, pieces, 0),
            1);
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(algorithm->GetOutputDataObject(0));
  return copy;
}

/// The pieces, in order, hold the whole's atoms in its order, every molecule in one piece, the
/// bonds once, and the same values of `arrays`.
void expect_pieces_make_the_whole(vtkAlgorithm* algorithm, int pieces,
                                  const std::vector<const char*>& arrays,
                                  double time = std::nan(""))
{
  const vtkSmartPointer<vtkPolyData> whole = piece_of(algorithm, 0, 1, time);
  ASSERT_GT(whole->GetNumberOfPoints(), 0);
  vtkIdType next = 0;
  vtkIdType bonds = 0;
  std::set<double> earlier_molecules;
  for (int piece = 0; piece < pieces; ++piece)
  {
    SCOPED_TRACE(piece);
    const vtkSmartPointer<vtkPolyData> part = piece_of(algorithm, piece, pieces, time);
    vtkDataArray* molecules = part->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    ASSERT_TRUE(part->GetNumberOfPoints() == 0 || molecules);
    std::set<double> here;
    for (vtkIdType a = 0; a < part->GetNumberOfPoints(); ++a, ++next)
    {
      ASSERT_LT(next, whole->GetNumberOfPoints());
      double p[3], q[3];
      part->GetPoint(a, p);
      whole->GetPoint(next, q);
      ASSERT_EQ(std::vector<double>(p, p + 3), std::vector<double>(q, q + 3)) << a;
      for (const char* name : arrays)
      {
        ASSERT_EQ(part->GetPointData()->GetArray(name)->GetComponent(a, 0),
                  whole->GetPointData()->GetArray(name)->GetComponent(next, 0))
          << name << " " << a;
      }
      here.insert(molecules->GetComponent(a, 0));
    }
    for (const double molecule : here)
    {
      EXPECT_EQ(earlier_molecules.count(molecule), 0u) << "molecule " << molecule << " split";
    }
    earlier_molecules.insert(here.begin(), here.end());
    EXPECT_EQ(part->GetNumberOfVerts(), part->GetNumberOfPoints());
    bonds += part->GetNumberOfLines();
  }
  EXPECT_EQ(next, whole->GetNumberOfPoints());
  EXPECT_EQ(bonds, whole->GetNumberOfLines());
}
} // namespace

TEST(MesoPieces, StructureReaderPiecesHoldWholeMolecules)
{
  vtkNew<vtkMesoStructureReader> reader; // HIV protease: two chains, a ligand, waters
  reader->SetFileName(data_file("proteins/1hpv.pdb").c_str());
  for (const int pieces : { 2, 3, 7 })
  {
    SCOPED_TRACE(pieces);
    expect_pieces_make_the_whole(reader, pieces, { vtkMesoArrayNames::AtomicNumber });
  }
  // More pieces than molecules: some are empty, none fails.
  reader->RemoveWatersOn();
  expect_pieces_make_the_whole(reader, 64, { vtkMesoArrayNames::AtomicNumber });
}

TEST(MesoPieces, TrajectoryPiecesFollowTheFrames)
{
  vtkNew<vtkMesoTrajectoryReader> reader; // YiiP in a POPE/POPG bilayer, 5 frames
  reader->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  reader->UpdateInformation();
  for (const double time : { 40000.0, 80000.0 })
  {
    SCOPED_TRACE(time);
    expect_pieces_make_the_whole(reader, 3, { vtkMesoArrayNames::AtomicNumber }, time);
  }
}

TEST(MesoPieces, FiltersOfWholeChainsComputeOnTheWholeAndKeepThePiece)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1hpv.pdb").c_str());
  // The two chains' β-sheet pairs across chains: DSSP of a piece must see the other chain.
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  expect_pieces_make_the_whole(dssp, 2, { vtkMesoArrayNames::SecondaryStructureId });
  vtkNew<vtkMesoSurfaceArea> area;
  area->SetInputConnection(reader->GetOutputPort());
  expect_pieces_make_the_whole(area, 3, { vtkMesoArrayNames::AccessibleArea });
  // The surface of the whole is piece 0's; the others draw nothing twice.
  vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  const vtkIdType whole = piece_of(surface, 0, 1)->GetNumberOfPolys();
  EXPECT_GT(whole, 0);
  EXPECT_EQ(piece_of(surface, 0, 2)->GetNumberOfPolys(), whole);
  EXPECT_EQ(piece_of(surface, 1, 2)->GetNumberOfPolys(), 0);
}

TEST(MesoPieces, TheCutawayHidesTheSameMoleculesInPieces)
{
  vtkNew<vtkMesoTrajectoryReader> membrane; // POPE/POPG with YiiP
  membrane->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  membrane->RemoveWatersOn();
  membrane->Update();
  double centre[3];
  membrane->GetOutput()->GetCenter(centre);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(centre);
  plane->SetNormal(1, 0, 0);
  vtkNew<vtkMesoStructuredCutaway> cut;
  cut->SetInputConnection(membrane->GetOutputPort());
  cut->SetCutFunction(plane);
  cut->SetFractionHidden(0.6);
  cut->ExtractVisibleAtomsOn();
  const vtkSmartPointer<vtkPolyData> whole = piece_of(cut, 0, 1);
  ASSERT_GT(whole->GetNumberOfPoints(), 0);
  std::multiset<double> expected, joined;
  vtkDataArray* ids = whole->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  for (vtkIdType a = 0; a < whole->GetNumberOfPoints(); ++a)
  {
    expected.insert(ids->GetComponent(a, 0));
  }
  for (int piece = 0; piece < 3; ++piece)
  {
    const vtkSmartPointer<vtkPolyData> part = piece_of(cut, piece, 3);
    vtkDataArray* part_ids = part->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    for (vtkIdType a = 0; a < part->GetNumberOfPoints(); ++a)
    {
      joined.insert(part_ids->GetComponent(a, 0));
    }
  }
  EXPECT_LT(expected.size(), std::size_t(membrane->GetOutput()->GetNumberOfPoints()));
  EXPECT_EQ(joined, expected);
}
