// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the structured cutaway (mesolens::StructuredCutaway) for arbitrary
// molecules, types and cuts (planes, balls, boxes, NaN among them) on arbitrary structure meshes
// (a closed sphere, a bent grid, a soup of triangles that may be degenerate, far or NaN), with
// every setting at and past its limits. Every input must give a visibility mask or a
// mesolens::Error; the mask must keep every molecule outside the cut and hide, per type,
// round(fraction x molecules inside) of those inside. The structure mesh itself, the costly
// part, has its own target (fuzz_structure_mesh).
#include "fuzz_input.h"
#include "fuzz_molecule_cloud.h"

#include "mesolens/common/errors.h"
#include "mesolens/cutaway/structured_cutaway.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace {

using mesolens_fuzz::require;

/// A closed, fine enough sphere of radius 50 around the clouds.
mesolens::TriangleMesh octahedron_sphere()
{
  mesolens::TriangleMesh mesh;
  mesh.points = { 50, 0, 0, -50, 0, 0, 0, 50, 0, 0, -50, 0, 0, 0, 50, 0, 0, -50 };
  mesh.triangles = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
  return mesh;
}

/// A grid of n x n quads over the flat bilayer's 60 x 60 Å, its heights from the input.
mesolens::TriangleMesh bent_grid(mesolens_fuzz::FuzzInput& input)
{
  const std::size_t n = 1 + input.byte() % 8;
  mesolens::TriangleMesh mesh;
  for (std::size_t j = 0; j <= n; ++j)
  {
    for (std::size_t i = 0; i <= n; ++i)
    {
      mesh.points.insert(
        mesh.points.end(),
        { 60.0 * double(i) / double(n), 60.0 * double(j) / double(n), input.ranged(-30, 30) });
    }
  }
  for (std::size_t j = 0; j < n; ++j)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const auto corner = std::int64_t(j * (n + 1) + i), row = std::int64_t(n + 1);
      mesh.triangles.insert(
        mesh.triangles.end(),
        { corner, corner + 1, corner + row + 1, corner, corner + row + 1, corner + row });
    }
  }
  return mesh;
}

/// Up to 16 triangles anywhere, corners shared or repeated at random.
mesolens::TriangleMesh triangle_soup(mesolens_fuzz::FuzzInput& input)
{
  mesolens::TriangleMesh mesh;
  const std::size_t points = 3 + input.byte() % 14;
  for (std::size_t p = 0; p < 3 * points; ++p)
  {
    mesh.points.push_back(input.ranged(-60, 60));
  }
  const std::size_t triangles = input.byte() % 17;
  for (std::size_t k = 0; k < 3 * triangles; ++k)
  {
    mesh.triangles.push_back(std::int64_t(input.byte() % points));
  }
  return mesh;
}

mesolens::CutRegion cut_region(mesolens_fuzz::FuzzInput& input)
{
  mesolens::CutRegion cut;
  const std::uint8_t parts = input.byte();
  for (int k = 0; k < (parts & 3); ++k)
  {
    cut.planes.push_back({ { input.ranged(-60, 60), input.ranged(-60, 60), input.ranged(-60, 60) },
                           { input.ranged(-1, 1), input.ranged(-1, 1), input.ranged(-1, 1) } });
  }
  for (int k = 0; k < ((parts >> 2) & 3); ++k)
  {
    cut.balls.push_back({ { input.ranged(-60, 60), input.ranged(-60, 60), input.ranged(-60, 60) },
                          input.ranged(-5, 80) });
  }
  for (int k = 0; k < ((parts >> 4) & 3); ++k)
  {
    cut.boxes.push_back(
      { { input.ranged(-60, 60), input.ranged(-60, 60), input.ranged(-60, 60) },
        { input.ranged(-60, 60), input.ranged(-60, 60), input.ranged(-60, 60) } });
  }
  return cut;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  const std::vector<double> centres = molecule_cloud(input);
  const std::size_t molecules = centres.size() / 3;

  const mesolens::TriangleMesh structure = (options & 3) == 1 ? bent_grid(input)
    : (options & 3) == 2                                      ? triangle_soup(input)
                                                              : octahedron_sphere();

  std::vector<int> types(molecules);
  for (int& type : types)
  {
    type = input.byte() % 3;
  }
  mesolens::CutawayParams settings;
  settings.k = input.ranged(-1.05, 1.05);
  settings.fraction_hidden = input.ranged(-0.05, 1.05);
  if (options & 32)
  {
    settings.fraction_by_type[1] = input.ranged(0, 1);
  }
  const std::uint8_t modes = input.byte();
  settings.inverted = modes & 1;
  settings.random = modes & 2;
  settings.probabilistic = modes & 4;
  settings.seed = input.byte();
  const mesolens::CutRegion cut = cut_region(input);
  try
  {
    const mesolens::StructuredCutaway cutaway(structure, centres, types);
    require(cutaway.molecule_count() == molecules);
    const std::vector<std::uint8_t> visible = cutaway.visibility(cut, settings);
    require(visible.size() == molecules);
    std::map<int, std::size_t> inside, hidden;
    for (std::size_t m = 0; m < molecules; ++m)
    {
      const bool in_cut = cut.contains({ centres[3 * m], centres[3 * m + 1], centres[3 * m + 2] });
      require(in_cut || visible[m] == 1);
      inside[types[m]] += in_cut;
      hidden[types[m]] += visible[m] == 0;
    }
    for (const auto& [type, count] : inside)
    {
      const auto by_type = settings.fraction_by_type.find(type);
      const double fraction =
        by_type != settings.fraction_by_type.end() ? by_type->second : settings.fraction_hidden;
      require(hidden[type] == std::size_t(std::llround(fraction * double(count))));
    }
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
