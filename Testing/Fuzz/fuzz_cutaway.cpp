// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the structured cutaway: the structure mesh of a molecule cloud
// (mesolens::structure_mesh; one input in eight, it is the costly part) and the cutaway on it
// (mesolens::StructuredCutaway) for arbitrary molecules, types and cuts (planes, balls, boxes,
// NaN among them) and every setting at and past its limits. Every input must give a mesh and a
// visibility mask, or a mesolens::Error; the mask must keep every molecule outside the cut and
// hide, per type, round(fraction x molecules inside) of those inside.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/cutaway/structured_cutaway.h"
#include "mesolens/mesh/mesh_report.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace {

using mesolens_fuzz::require;

/// A cloud of molecule centres: a flat bilayer, a vesicle's two shells, or scattered points, with
/// some made to coincide or line up.
std::vector<double> molecule_cloud(mesolens_fuzz::FuzzInput& input)
{
  const std::uint8_t shape = input.byte();
  const std::size_t count = 4 + input.byte() % 120;
  std::vector<double> points;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double u = input.ranged(0, 1), v = input.ranged(0, 1);
    const double leaflet = (i % 2) ? 1.0 : -1.0;
    switch (shape % 3)
    {
      case 0:
        points.insert(points.end(), { 60 * u, 60 * v, 20 * leaflet });
        break;
      case 1: {
        const double theta = std::acos(1 - 2 * u), phi = 2 * M_PI * v, r = 50 + 10 * leaflet;
        points.insert(points.end(),
                      { r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                        r * std::cos(theta) });
        break;
      }
      default:
        points.insert(points.end(),
                      { input.ranged(-50, 50), input.ranged(-50, 50), input.ranged(-50, 50) });
    }
    const std::uint8_t twist = input.byte();
    if (twist < 8 && i > 0) // onto the previous point
    {
      std::copy_n(&points[3 * (i - 1)], 3, &points[3 * i]);
    }
    else if (twist < 12) // onto one line
    {
      points[3 * i + 1] = points[3 * i + 2] = 0;
    }
  }
  return points;
}

/// A closed, fine enough sphere of radius 50 for the cutaway when the structure mesh is not made.
mesolens::TriangleMesh octahedron_sphere()
{
  mesolens::TriangleMesh mesh;
  mesh.points = { 50, 0, 0, -50, 0, 0, 0, 50, 0, 0, -50, 0, 0, 0, 50, 0, 0, -50 };
  mesh.triangles = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
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

  mesolens::TriangleMesh structure = octahedron_sphere();
  if ((options & 7) == 0)
  {
    mesolens::StructureMeshParams params;
    params.vertices = std::size_t(input.byte()) * 3;
    params.edge_length = (options & 8) ? input.ranged(-1, 30) : 0;
    params.mid_surface_radius = (options & 16) ? input.ranged(-1, 60) : 0;
    // Meshes past this limit are refused (counts asked here reach 765, so both ways are
    // tried): the angle repair of a poor first mesh takes about 1.5 ms per vertex, ten times
    // that under the sanitizers, and 800 vertices overran the 10 s timeout.
    params.vertex_limit = 400;
    try
    {
      structure = mesolens::structure_mesh(centres, params);
      const mesolens::MeshReport report = mesolens::mesh_report(structure.view());
      require(report.is_manifold() && report.components == 1);
    }
    catch (const mesolens::Error&)
    {
      return 0;
    }
  }

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
