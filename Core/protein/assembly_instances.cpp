// SPDX-License-Identifier: GPL-3.0-or-later
// assembly_instances(): an assembly as instance matrices over the asymmetric unit.
#include "mesolens/protein/assembly.h"

#include "mesolens/common/errors.h"
#include "protein/detail/assembly_reach.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

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

AssemblyAtomClasses assembly_atom_classes(const AssemblyInstances& instances,
                                          std::size_t atom_count)
{
  const std::size_t sets = instances.atom_sets.size();
  for (std::size_t copy = 0; copy < instances.instances.size(); ++copy)
  {
    if (instances.instances[copy].atom_set >= sets)
    {
      throw InvalidInput("assembly copy " + std::to_string(copy) + " names atom set " +
                         std::to_string(instances.instances[copy].atom_set) + " of " +
                         std::to_string(sets));
    }
  }
  // Partition refinement: each set splits every class it meets into its part and the rest.
  std::vector<std::uint32_t> class_of(atom_count, 0);
  std::uint32_t classes = 1;
  std::vector<std::int64_t> split_to;
  for (std::size_t s = 0; s < sets; ++s)
  {
    split_to.assign(classes, -1);
    for (const std::uint32_t atom : instances.atom_sets[s].atoms)
    {
      if (atom >= atom_count)
      {
        throw InvalidInput("assembly atom set " + std::to_string(s) + " holds row " +
                           std::to_string(atom) + " of a table of " + std::to_string(atom_count) +
                           " atoms: the copies were made for another asymmetric unit");
      }
      std::int64_t& target = split_to[class_of[atom]];
      if (target < 0)
      {
        target = classes++;
      }
      class_of[atom] = static_cast<std::uint32_t>(target);
    }
  }
  // Numbered by first row, without the classes that splitting emptied.
  AssemblyAtomClasses result;
  std::vector<std::int64_t> number(classes, -1);
  result.class_of_atom.resize(atom_count);
  for (std::size_t atom = 0; atom < atom_count; ++atom)
  {
    std::int64_t& k = number[class_of[atom]];
    if (k < 0)
    {
      k = static_cast<std::int64_t>(result.count++);
    }
    result.class_of_atom[atom] = static_cast<std::uint32_t>(k);
  }
  result.in_set.assign(result.count * sets, 0);
  for (std::size_t s = 0; s < sets; ++s)
  {
    for (const std::uint32_t atom : instances.atom_sets[s].atoms)
    {
      result.in_set[result.class_of_atom[atom] * sets + s] = 1;
    }
  }
  return result;
}

} // namespace mesolens
