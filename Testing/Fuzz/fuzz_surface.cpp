// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the molecular surface (mesolens::molecular_surface, all three kinds) and the
// exact sphere-union area (mesolens::sphere_union_area) on arbitrary sphere sets: coincident,
// nearly coincident, collinear and cospherical centres, tiny and huge radii, probe radii and
// tolerances at and past their limits, non-finite numbers. Every input must give a surface or
// a mesolens::Error; a surface must be a closed mesh of finite points whose triangles name its
// vertices, and its exact figures finite where the input is not exactly degenerate.
//
// Input: a byte of options (bits 0-1 the kind, 2 cavities dropped, 3 no mesh, 4 no exact
// figures), the probe radius and tolerance, then per sphere a byte saying how its centre is
// made (fresh, on top of or next to an earlier one, on the line of the first two, on the sphere
// around the first) and its numbers. At most 12 spheres, and inputs whose mesh would pass about
// 4000 triangles are skipped: the target looks for wrong results, not for large ones.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/surface/molecular_surface.h"
#include "mesolens/surface/sphere_union_area.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using mesolens_fuzz::require;

std::vector<double> sphere_centres(mesolens_fuzz::FuzzInput& input, std::vector<double>& radii)
{
  std::vector<double> centres;
  const std::size_t count = input.byte() % 13;
  for (std::size_t i = 0; i < count && !input.empty(); ++i)
  {
    const std::uint8_t how = input.byte();
    double c[3];
    const std::size_t made = centres.size() / 3;
    const std::size_t earlier = made ? input.byte() % made : 0;
    switch (made ? how % 6 : 0)
    {
      case 1: // on top of an earlier centre
        for (int d = 0; d < 3; ++d)
          c[d] = centres[3 * earlier + d];
        break;
      case 2: // next to an earlier one, by a hair
        for (int d = 0; d < 3; ++d)
          c[d] = centres[3 * earlier + d] + input.ranged(-1e-6, 1e-6);
        break;
      case 3: // on the line of the first two
      {
        const std::size_t second = made > 1 ? 1 : 0;
        const double t = input.ranged(-2.0, 3.0);
        for (int d = 0; d < 3; ++d)
          c[d] = centres[d] + t * (centres[3 * second + d] - centres[d]);
        break;
      }
      case 4: // on a sphere around the first
      {
        const double theta = input.ranged(0, M_PI), phi = input.ranged(0, 2 * M_PI);
        const double r = input.ranged(0.5, 4.0);
        c[0] = centres[0] + r * std::sin(theta) * std::cos(phi);
        c[1] = centres[1] + r * std::sin(theta) * std::sin(phi);
        c[2] = centres[2] + r * std::cos(theta);
        break;
      }
      default:
        for (double& x : c)
          x = input.ranged(-8.0, 8.0);
    }
    centres.insert(centres.end(), c, c + 3);
    const std::uint8_t size = input.byte();
    radii.push_back(size < 16 ? input.ranged(1e-4, 0.05) : input.ranged(0.5, 3.0));
  }
  return centres;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options_byte = input.byte();
  mesolens::MolecularSurfaceParams options;
  options.kind = mesolens::SurfaceKind(options_byte % 3);
  options.keep_cavities = !(options_byte & 4);
  options.tessellate = !(options_byte & 8);
  options.exact_figures = !(options_byte & 16);
  options.probe_radius = input.ranged(0.0, 3.0);
  options.tolerance = input.ranged(0.004, 1.2);
  std::vector<double> radii;
  const std::vector<double> centres = sphere_centres(input, radii);

  // The work cap: triangles grow as the area over the tolerance squared.
  double area = 0;
  for (const double r : radii)
  {
    const double inflated = r + (std::isfinite(options.probe_radius) ? options.probe_radius : 0);
    area += 4 * M_PI * inflated * inflated;
  }
  if (options.tessellate && std::isfinite(options.tolerance) && options.tolerance > 0 &&
      area / (options.tolerance * options.tolerance) > 4000)
  {
    return 0;
  }
  try
  {
    const mesolens::SphereUnionArea union_area = mesolens::sphere_union_area(centres, radii);
    require(union_area.per_sphere.size() == radii.size());
    require(std::isfinite(union_area.total) && union_area.total >= 0);
    require(std::isfinite(union_area.volume) && union_area.volume >= -1e-9);
  }
  catch (const mesolens::Error&)
  {
  }
  try
  {
    const mesolens::MolecularSurface surface = mesolens::molecular_surface(centres, radii, options);
    for (const double x : surface.points)
    {
      require(std::isfinite(x));
    }
    require(surface.normals.size() == surface.points.size());
    require(surface.atom.size() == surface.points.size() / 3);
    mesolens_fuzz::require_closed_mesh(surface.points.size() / 3, surface.triangles);
    if (options.exact_figures && surface.degenerate_vertex_count == 0)
    {
      require(std::isfinite(surface.area) && surface.area >= 0);
    }
  }
  catch (const mesolens::SolverFailure& failure)
  {
    // Users get this error rather than a crash, but it is a defect of the surface's field.
    require(std::string(failure.what()).find("contour is inconsistent") == std::string::npos);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
