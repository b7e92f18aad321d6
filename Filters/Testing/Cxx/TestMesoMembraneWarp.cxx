// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoMembraneWarp.h"

#include "mesolens/common/errors.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>

#include <gtest/gtest.h>

namespace {

mesolens::MembraneWarp full_warp()
{
  mesolens::MembraneWarp warp;
  warp.method = mesolens::MappingMethod::Polynomial;
  warp.tiles = 2;
  warp.tiles_requested = 3;
  warp.cut_to_disk = false;
  warp.note = "mapped 2 x 2 tiles of the 3 x 3 asked";
  warp.scale = 1e-4;
  warp.origin = { -1.5, 2.25 };
  warp.a = { 64.2, 0.5 };
  warp.b = { -0.25, 63.9 };
  warp.centre_height = 31.5;
  warp.layer_half_thickness = 22;
  warp.geodesic_radius = 0.0513;
  warp.seed_uv = { 0.001, -0.002 };
  warp.seed_normal = { 0.6, 0, 0.8 };
  warp.refinement_levels = 3;
  warp.polynomial_splits = { 1, 2, 1, 1 };
  for (int i = 0; i < 30 * 7; ++i)
  {
    warp.polynomial_coefficients.push_back(0.125 * i - 3);
  }
  warp.polynomial_rms_residual = { 0.1, 0.2, 0.3, 0.4 };
  warp.polynomial_max_residual = { 0.5, 0.6, 0.7, 0.8 };
  warp.tile_fallback = { 0, 0, 1, 0 };
  for (int i = 0; i < 4 * 3; ++i)
  {
    warp.instance_molecules.push_back(10 + i % 3);
    warp.instance_tiles.push_back(i / 3);
    for (int k = 0; k < 16; ++k)
    {
      warp.instance_matrices.push_back(i + 0.01 * k);
    }
  }
  return warp;
}

TEST(MesoMembraneWarp, WhatIsWrittenIsReadBack)
{
  const mesolens::MembraneWarp written = full_warp();
  vtkNew<vtkFieldData> fields;
  vtkMesoMembraneWarp::Write(written, fields);
  mesolens::MembraneWarp read;
  ASSERT_TRUE(vtkMesoMembraneWarp::Read(fields, read));
  EXPECT_EQ(read.method, written.method);
  EXPECT_EQ(read.tiles, written.tiles);
  EXPECT_EQ(read.tiles_requested, written.tiles_requested);
  EXPECT_EQ(read.cut_to_disk, written.cut_to_disk);
  EXPECT_EQ(read.note, written.note);
  EXPECT_EQ(read.scale, written.scale);
  EXPECT_EQ(read.origin, written.origin);
  EXPECT_EQ(read.a, written.a);
  EXPECT_EQ(read.b, written.b);
  EXPECT_EQ(read.centre_height, written.centre_height);
  EXPECT_EQ(read.layer_half_thickness, written.layer_half_thickness);
  EXPECT_EQ(read.geodesic_radius, written.geodesic_radius);
  EXPECT_EQ(read.seed_uv, written.seed_uv);
  EXPECT_EQ(read.seed_normal, written.seed_normal);
  EXPECT_EQ(read.refinement_levels, written.refinement_levels);
  EXPECT_EQ(read.polynomial_coefficients, written.polynomial_coefficients);
  EXPECT_EQ(read.polynomial_splits, written.polynomial_splits);
  EXPECT_EQ(read.polynomial_rms_residual, written.polynomial_rms_residual);
  EXPECT_EQ(read.polynomial_max_residual, written.polynomial_max_residual);
  EXPECT_EQ(read.tile_fallback, written.tile_fallback);
  EXPECT_EQ(read.instance_matrices, written.instance_matrices);
  EXPECT_EQ(read.instance_molecules, written.instance_molecules);
  EXPECT_EQ(read.instance_tiles, written.instance_tiles);
  // The arrays keep their names and shapes (what scripts read).
  EXPECT_EQ(fields->GetArray(vtkMesoArrayNames::PolynomialCoefficients)->GetNumberOfComponents(),
            30);
  EXPECT_EQ(fields->GetArray(vtkMesoArrayNames::InstanceMatrices)->GetNumberOfTuples(), 12);
  EXPECT_EQ(fields->GetArray(vtkMesoArrayNames::TilesMapped)->GetTuple1(0), 2.0);
}

TEST(MesoMembraneWarp, AnythingElseIsNotAWarp)
{
  mesolens::MembraneWarp warp;
  EXPECT_FALSE(vtkMesoMembraneWarp::Read(nullptr, warp));
  vtkNew<vtkFieldData> empty;
  EXPECT_FALSE(vtkMesoMembraneWarp::Read(empty, warp));
  // Each array of the frame, the tiles and the method is needed.
  for (const char* needed :
       { vtkMesoArrayNames::PatchOrigin, vtkMesoArrayNames::PatchCellA,
         vtkMesoArrayNames::PatchCellB, vtkMesoArrayNames::PatchCentreHeight,
         vtkMesoArrayNames::LayerHalfThickness, vtkMesoArrayNames::Tiles,
         vtkMesoArrayNames::MappingMethod })
  {
    vtkNew<vtkFieldData> fields;
    vtkMesoMembraneWarp::Write(full_warp(), fields);
    fields->RemoveArray(needed);
    EXPECT_FALSE(vtkMesoMembraneWarp::Read(fields, warp)) << needed;
  }
  // A coefficient array of the wrong shape is read as none, which cannot be drawn.
  vtkNew<vtkFieldData> fields;
  vtkMesoMembraneWarp::Write(full_warp(), fields);
  vtkNew<vtkDoubleArray> wrong;
  wrong->SetName(vtkMesoArrayNames::PolynomialCoefficients);
  wrong->SetNumberOfComponents(10);
  wrong->SetNumberOfTuples(21);
  wrong->Fill(0.0);
  fields->AddArray(wrong);
  ASSERT_TRUE(vtkMesoMembraneWarp::Read(fields, warp));
  EXPECT_TRUE(warp.polynomial_coefficients.empty());
  EXPECT_THROW(mesolens::check_drawable(warp), mesolens::InvalidInput);
}

} // namespace
