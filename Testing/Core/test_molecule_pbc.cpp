// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecule_pbc.h"

#include "mesolens/errors.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
mesolens::PeriodicBox cube(double edge)
{
  mesolens::PeriodicBox box;
  box.vectors = { { { edge, 0, 0 }, { 0, edge, 0 }, { 0, 0, edge } } };
  return box;
}
} // namespace

TEST(MoleculePbc, MakesSplitMoleculeWhole)
{
  // A three-atom chain wrapped around x = 0 of a 30 Å box, then a second molecule.
  std::vector<float> p = { 29.0f, 5, 5, 0.5f, 5, 5, 2.0f, 5, 5, 15, 15, 15 };
  const std::vector<int> molecules = { 0, 0, 0, 1 };
  mesolens::make_molecules_whole(p.data(), molecules.data(), 4, cube(30));
  EXPECT_FLOAT_EQ(p[0], 29.0f);
  EXPECT_FLOAT_EQ(p[3], 30.5f);
  EXPECT_FLOAT_EQ(p[6], 32.0f);
  EXPECT_FLOAT_EQ(p[9], 15.0f);
}

TEST(MoleculePbc, TriclinicBoxWhole)
{
  const auto box = mesolens::PeriodicBox::from_cell(40, 40, 40, 60, 60, 90);
  // Two atoms 1 Å apart, the second moved by the c vector.
  std::vector<float> p = { 1, 1, 1, 2, 1, 1 };
  for (int k = 0; k < 3; ++k)
  {
    p[3 + k] = float(p[3 + k] + box.vectors[2][k]);
  }
  const std::vector<int> molecules = { 0, 0 };
  mesolens::make_molecules_whole(p.data(), molecules.data(), 2, box);
  EXPECT_NEAR(p[3], 2.0f, 1e-4);
  EXPECT_NEAR(p[4], 1.0f, 1e-4);
  EXPECT_NEAR(p[5], 1.0f, 1e-4);
}

TEST(MoleculePbc, UnsetBoxIsNoOp)
{
  std::vector<float> p = { 29.0f, 5, 5, 0.5f, 5, 5 };
  const std::vector<int> molecules = { 0, 0 };
  mesolens::make_molecules_whole(p.data(), molecules.data(), 2, mesolens::PeriodicBox{});
  EXPECT_FLOAT_EQ(p[3], 0.5f);
}

TEST(MoleculePbc, ContinuityUndoesBoxCrossings)
{
  // One molecule drifting +4 Å per frame along x in a 10 Å box, wrapped by the simulation.
  const auto box = cube(10);
  mesolens::MoleculeContinuity continuity({ 0, 0 });
  std::vector<std::vector<float>> frames;
  for (int f = 0; f < 6; ++f)
  {
    const double x = 1.0 + 4.0 * f;
    const float wrapped = float(std::fmod(x, 10.0));
    frames.push_back({ wrapped, 0, 0, wrapped + 0.5f, 0, 0 });
  }
  for (std::size_t f = 0; f < frames.size(); ++f)
  {
    std::vector<float> p = frames[f];
    continuity.add_frame(f, p.data(), box);
    EXPECT_NEAR(p[0], 1.0 + 4.0 * f, 1e-4) << f;
  }
  // Random access afterwards gives the same continuous positions.
  std::vector<float> p = frames[3];
  continuity.apply(3, p.data(), box);
  EXPECT_NEAR(p[0], 13.0, 1e-4);
  EXPECT_THROW(continuity.apply(9, p.data(), box), mesolens::InvalidInput);
  EXPECT_THROW(continuity.add_frame(9, p.data(), box), mesolens::InvalidInput);
}

TEST(MoleculePbc, ContinuityAcrossCheckpoints)
{
  // 200 frames (several checkpoints) of a molecule drifting 3 Å per frame in a 10 Å box, and a
  // resting one: random access to any frame gives the unwrapped position.
  const auto box = cube(10);
  mesolens::MoleculeContinuity continuity({ 0, 1 });
  auto wrapped_frame = [](std::size_t f) {
    const double x = 1.0 + 3.0 * double(f);
    return std::vector<float>{ float(std::fmod(x, 10.0)), 0, 0, 5, 5, 5 };
  };
  for (std::size_t f = 0; f < 200; ++f)
  {
    std::vector<float> p = wrapped_frame(f);
    continuity.add_frame(f, p.data(), box);
  }
  for (std::size_t f : { 199u, 0u, 64u, 65u, 130u, 63u })
  {
    std::vector<float> p = wrapped_frame(f);
    continuity.apply(f, p.data(), box);
    EXPECT_NEAR(p[0], 1.0 + 3.0 * double(f), 1e-3) << f;
    EXPECT_FLOAT_EQ(p[3], 5.0f);
  }
}
