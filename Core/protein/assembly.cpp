// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/assembly.h"

#include "mesolens/common/errors.h"

#include <Eigen/Geometry>

#include <cmath>
#include <unordered_set>

namespace mesolens {

AssemblyMatrix compose(const AssemblyMatrix& left, const AssemblyMatrix& right)
{
  AssemblyMatrix product{};
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      double sum = j == 3 ? left[std::size_t(4 * i + 3)] : 0.0;
      for (int k = 0; k < 3; ++k)
      {
        sum += left[std::size_t(4 * i + k)] * right[std::size_t(4 * k + j)];
      }
      product[std::size_t(4 * i + j)] = sum;
    }
  }
  return product;
}

std::array<double, 3> transform_point(const AssemblyMatrix& m, const std::array<double, 3>& p)
{
  return { m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3],
           m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
           m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11] };
}

std::array<double, 4> rotation_quaternion(const AssemblyMatrix& matrix)
{
  Eigen::Matrix3d rotation;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      rotation(i, j) = matrix[std::size_t(4 * i + j)];
    }
  }
  constexpr double tolerance = 1e-3;
  const double off_identity =
    (rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off_identity <= tolerance) || !(std::abs(rotation.determinant() - 1.0) <= tolerance))
  {
    throw InvalidInput("the assembly operator is not a rotation (R R^T differs from I by " +
                       std::to_string(off_identity) +
                       ", det R = " + std::to_string(rotation.determinant()) +
                       "): its copy cannot be drawn as a rotated instance");
  }
  Eigen::Quaterniond q(rotation);
  q.normalize();
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  return { sign * q.w(), sign * q.x(), sign * q.y(), sign * q.z() };
}

std::size_t Assembly::copy_count() const
{
  std::size_t count = 0;
  for (const AssemblyGenerator& generator : this->generators)
  {
    count += generator.operators.size();
  }
  return count;
}

const Assembly* find_assembly(const std::vector<Assembly>& assemblies, const std::string& name)
{
  for (const Assembly& assembly : assemblies)
  {
    if (assembly.name == name)
    {
      return &assembly;
    }
  }
  return nullptr;
}

std::string assembly_chain_name(const std::string& chain, std::size_t copy)
{
  return copy == 0 ? chain : chain + "-" + std::to_string(copy + 1);
}

std::vector<std::uint32_t> generator_atoms(const AtomTable& table,
                                           const AssemblyGenerator& generator)
{
  const bool by_label = generator.chain_ids == AssemblyChainIds::Label;
  const std::vector<std::string>& ids = by_label ? table.label_asym_ids : table.chain_ids;
  if (ids.size() != table.size())
  {
    throw InvalidInput(std::string("the assembly names chains by their ") +
                       (by_label ? "mmCIF label_asym_ids" : "author chain ids") +
                       ", which the atom table does not have (" + std::to_string(ids.size()) +
                       " ids for " + std::to_string(table.size()) + " atoms)");
  }
  const std::unordered_set<std::string> chains(generator.chains.begin(), generator.chains.end());
  std::vector<std::uint32_t> rows;
  bool selected = false;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (i == 0 || ids[i] != ids[i - 1]) // chains come in runs: decide once per run
    {
      selected = chains.count(ids[i]) > 0;
    }
    if (selected)
    {
      rows.push_back(std::uint32_t(i));
    }
  }
  return rows;
}

std::size_t assembly_atom_count(const AtomTable& asymmetric_unit, const Assembly& assembly)
{
  std::size_t count = 0;
  for (const AssemblyGenerator& generator : assembly.generators)
  {
    if (!generator.operators.empty())
    {
      count += generator_atoms(asymmetric_unit, generator).size() * generator.operators.size();
    }
  }
  return count;
}

} // namespace mesolens
