// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_pbc.h"

#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

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
  mesolens::make_molecules_whole(p, molecules.data(), cube(30));
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
  mesolens::make_molecules_whole(p, molecules.data(), box);
  EXPECT_NEAR(p[3], 2.0f, 1e-4);
  EXPECT_NEAR(p[4], 1.0f, 1e-4);
  EXPECT_NEAR(p[5], 1.0f, 1e-4);
}

TEST(MoleculePbc, WholeMoleculesEqualTheReductionOfEveryStep)
{
  // Random chains of steps from 0.5 to 14 Å in a skewed box, each atom moved by a random number
  // of box vectors (so some raw steps are short and the rest span the box): the same floats as
  // reducing every step to its minimum image, as it was done before short steps were left alone.
  const auto box = mesolens::PeriodicBox::from_cell(40, 45, 50, 70, 80, 100);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), length(0.5, 14.0), where(0.0, 40.0);
  std::vector<float> positions;
  std::vector<int> molecules;
  for (int m = 0; m < 50; ++m)
  {
    std::array<double, 3> at{ where(random), where(random), where(random) };
    for (int k = 0; k < 30; ++k)
    {
      std::array<double, 3> direction{ unit(random), unit(random), unit(random) };
      const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] +
                                    direction[2] * direction[2]);
      const double step = length(random);
      for (int c = 0; c < 3; ++c)
      {
        at[c] += step * direction[c] / norm;
      }
      // Wrapped by a random whole number of each box vector.
      std::array<double, 3> wrapped = at;
      for (int v = 0; v < 3; ++v)
      {
        const int times = int(std::floor(3 * unit(random)));
        for (int c = 0; c < 3; ++c)
        {
          wrapped[c] += times * box.vectors[v][c];
        }
      }
      positions.insert(positions.end(),
                       { float(wrapped[0]), float(wrapped[1]), float(wrapped[2]) });
      molecules.push_back(m);
    }
  }
  std::vector<float> reference = positions;
  for (std::size_t a = 1; a < molecules.size(); ++a)
  {
    if (molecules[a] != molecules[a - 1])
    {
      continue;
    }
    float* p = reference.data() + 3 * a;
    const float* q = reference.data() + 3 * (a - 1);
    const auto d =
      box.minimum_image({ double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2] });
    for (int c = 0; c < 3; ++c)
    {
      p[c] = float(double(q[c]) + d[std::size_t(c)]);
    }
  }
  mesolens::make_molecules_whole(positions, molecules.data(), box);
  EXPECT_EQ(positions, reference);
}

TEST(MoleculePbc, UnsetBoxIsNoOp)
{
  std::vector<float> p = { 29.0f, 5, 5, 0.5f, 5, 5 };
  const std::vector<int> molecules = { 0, 0 };
  mesolens::make_molecules_whole(p, molecules.data(), mesolens::PeriodicBox{});
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
    continuity.add_frame(f, p, box);
    EXPECT_NEAR(p[0], 1.0 + 4.0 * f, 1e-4) << f;
  }
  // Random access afterwards gives the same continuous positions.
  std::vector<float> p = frames[3];
  continuity.apply(3, p, box);
  EXPECT_NEAR(p[0], 13.0, 1e-4);
  EXPECT_THROW(continuity.apply(9, p, box), mesolens::InvalidInput);
  EXPECT_THROW(continuity.add_frame(9, p, box), mesolens::InvalidInput);
  std::vector<float> three_atoms(9, 0.0f);
  EXPECT_THROW(continuity.apply(3, three_atoms, box), mesolens::InvalidInput);
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
    continuity.add_frame(f, p, box);
  }
  for (std::size_t f : { 199u, 0u, 64u, 65u, 130u, 63u })
  {
    std::vector<float> p = wrapped_frame(f);
    continuity.apply(f, p, box);
    EXPECT_NEAR(p[0], 1.0 + 3.0 * double(f), 1e-3) << f;
    EXPECT_FLOAT_EQ(p[3], 5.0f);
  }
}

TEST(AssemblyShifts, WholeAssembliesAndMembranesAcrossTheBoxStay)
{
  mesolens::PeriodicBox box;
  box.vectors = { { { 100, 0, 0 }, { 0, 100, 0 }, { 0, 0, 100 } } };
  // A whole ball of points past the box's middle (its periodic mean is at 0.8 of the box, the
  // same place as -0.2 of it): nothing moves.
  std::vector<double> ball;
  for (int i = 0; i < 200; ++i)
    ball.insert(ball.end(),
                { 80.0 + 10 * std::sin(i * 0.7), 80.0 + 10 * std::cos(i * 1.3),
                  60.0 + 10 * std::sin(i * 2.1) });
  for (const auto& shift : mesolens::assembly_shifts(ball, box))
    EXPECT_EQ(shift, (std::array<double, 3>{ 0, 0, 0 }));
  // A flat periodic membrane crossing the box in x and y, around z = 55: nothing moves either.
  std::vector<double> membrane;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (double z : { 40.0, 70.0 })
        membrane.insert(membrane.end(), { 5.0 * i + 1, 5.0 * j + 2, z });
  for (const auto& shift : mesolens::assembly_shifts(membrane, box))
    EXPECT_EQ(shift, (std::array<double, 3>{ 0, 0, 0 }));
}

TEST(AssemblyShifts, GathersAVesicleSplitByTheBoxFaces)
{
  // Points on a sphere of radius 10 around a box corner, wrapped into the box [0, 50)^3 (so the
  // sphere is in eight pieces), in an orthorhombic and in a triclinic box.
  for (bool triclinic : { false, true })
  {
    mesolens::PeriodicBox box;
    box.vectors = { { { 50, 0, 0 }, { triclinic ? 10.0 : 0.0, 50, 0 }, { 0, 0, 50 } } };
    std::vector<double> centres;
    const double golden = 3.14159265358979 * (3 - std::sqrt(5.0));
    for (int i = 0; i < 400; ++i)
    {
      const double z = 1 - 2 * (i + 0.5) / 400;
      const double r = std::sqrt(1 - z * z);
      std::array<double, 3> p{ 10 * r * std::cos(golden * i), 10 * r * std::sin(golden * i),
                               10 * z };
      // Into the box: subtract whole box vectors (fractional coordinates floored).
      const double fz = std::floor(p[2] / 50);
      const double fy = std::floor(p[1] / 50);
      p[0] -= fy * box.vectors[1][0];
      const double fx = std::floor(p[0] / 50);
      centres.insert(centres.end(), { p[0] - fx * 50, p[1] - fy * 50, p[2] - fz * 50 });
    }
    const auto shifts = mesolens::assembly_shifts(centres, box);
    ASSERT_EQ(shifts.size(), 400u);
    std::array<double, 3> mean{ 0, 0, 0 };
    for (std::size_t m = 0; m < 400; ++m)
      for (int d = 0; d < 3; ++d)
        mean[d] += (centres[3 * m + d] + shifts[m][d]) / 400;
    for (std::size_t m = 0; m < 400; ++m)
    {
      double squared = 0;
      for (int d = 0; d < 3; ++d)
      {
        const double v = centres[3 * m + d] + shifts[m][d] - mean[d];
        squared += v * v;
      }
      EXPECT_NEAR(std::sqrt(squared), 10.0, 0.01) << (triclinic ? "triclinic " : "") << m;
    }
  }
  // No box: no shifts.
  const auto none =
    mesolens::assembly_shifts(std::vector<double>{ 1, 2, 3 }, mesolens::PeriodicBox());
  EXPECT_EQ(none[0][0], 0.0);
}
