// SPDX-License-Identifier: GPL-3.0-or-later
// assembly_instances(): an assembly as instance matrices over the asymmetric unit.
#include "mesolens/protein/assembly.h"
#include "protein/detail/assembly_reach.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mesolens {

namespace {

/// The centre of the atoms' bounding box and the largest distance of an atom from it.
void bounding_sphere(const AtomTable& table, AssemblyAtomSet& set)
{
  if (set.atoms.empty())
  {
    return;
  }
  std::array<double, 3> low, high;
  low.fill(std::numeric_limits<double>::max());
  high.fill(std::numeric_limits<double>::lowest());
  for (const std::uint32_t i : set.atoms)
  {
    for (std::size_t d = 0; d < 3; ++d)
    {
      low[d] = std::min(low[d], double(table.positions[3 * i + d]));
      high[d] = std::max(high[d], double(table.positions[3 * i + d]));
    }
  }
  double radius_squared = 0;
  for (std::size_t d = 0; d < 3; ++d)
  {
    set.center[d] = 0.5 * (low[d] + high[d]);
  }
  for (const std::uint32_t i : set.atoms)
  {
    double squared = 0;
    for (std::size_t d = 0; d < 3; ++d)
    {
      const double offset = double(table.positions[3 * i + d]) - set.center[d];
      squared += offset * offset;
    }
    radius_squared = std::max(radius_squared, squared);
  }
  set.radius = std::sqrt(radius_squared);
}

/// The largest singular value of the matrix's linear part R (1 for a rotation): how much it
/// can stretch a radius.
double largest_stretch(const AssemblyMatrix& m)
{
  Eigen::Matrix3d r;
  r << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
  const Eigen::Matrix3d gram = r.transpose() * r;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(gram, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, solver.eigenvalues().maxCoeff()));
}

} // namespace

AssemblyInstances assembly_instances(const AtomTable& asymmetric_unit, const Assembly& assembly)
{
  AssemblyInstances result;
  std::map<std::vector<std::uint32_t>, std::size_t> set_of_rows;
  for (const AssemblyGenerator& generator : assembly.generators)
  {
    std::vector<std::uint32_t> rows = generator_atoms(asymmetric_unit, generator);
    detail::check_float_reach(asymmetric_unit, rows, generator, assembly.name);
    const auto found = set_of_rows.emplace(rows, result.atom_sets.size());
    if (found.second)
    {
      AssemblyAtomSet set;
      set.whole_table = rows.size() == asymmetric_unit.size();
      set.atoms = std::move(rows);
      bounding_sphere(asymmetric_unit, set);
      result.atom_sets.push_back(std::move(set));
    }
    const AssemblyAtomSet& set = result.atom_sets[found.first->second];
    for (const AssemblyOperator& op : generator.operators)
    {
      AssemblyInstance instance;
      instance.matrix = op.matrix;
      instance.atom_set = found.first->second;
      instance.center = transform_point(op.matrix, set.center);
      instance.radius = set.radius * largest_stretch(op.matrix);
      result.instances.push_back(instance);
    }
  }
  return result;
}

} // namespace mesolens
