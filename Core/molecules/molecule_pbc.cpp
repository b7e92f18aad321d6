// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_pbc.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_groups.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>

namespace mesolens {

namespace {
Eigen::Matrix3d box_columns(const PeriodicBox& box)
{
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m(c, r) = box.vectors[std::size_t(r)][std::size_t(c)];
    }
  }
  return m;
}

} // namespace

void make_molecules_whole(PointSpan<float> positions, const int* molecule_ids,
                          const PeriodicBox& box)
{
  if (!box.is_set() || positions.size() == 0)
  {
    return;
  }
  make_molecules_whole(positions, group_molecules(molecule_ids, positions.size()), box);
}

void make_molecules_whole(PointSpan<float> positions, const MoleculeGroups& molecules,
                          const PeriodicBox& box)
{
  if (!box.is_set() || positions.size() == 0)
  {
    return;
  }
  if (molecules.of_atom.size() != positions.size())
  {
    throw InvalidInput("make_molecules_whole: molecules grouped for " +
                       std::to_string(molecules.of_atom.size()) + " atoms, " +
                       std::to_string(positions.size()) + " positions");
  }
  const MinimumImage minimum_image(box);
  // Steps shorter than half the smallest box height are their own minimum image (any other
  // image is longer by a box-vector combination, at least that height long): the bonded
  // neighbours that most steps are keep their place without a reduction. (The kept position
  // is bit for bit the one the reduction would give: float differences are exact in double.)
  const double half_height = 0.5 * box.smallest_height();
  const double short_step2 = half_height * half_height * (1.0 - 1e-9);
  // Each atom next to the previous atom of its molecule.
  for (std::size_t m = 0; m < molecules.count(); ++m)
  {
    const std::uint32_t* atom = molecules.atoms.data() + molecules.first[m];
    for (std::size_t k = 1; k < molecules.size_of(m); ++k)
    {
      float* p = positions[atom[k]];
      const float* q = positions[atom[k - 1]];
      const std::array<double, 3> step{ double(p[0]) - q[0], double(p[1]) - q[1],
                                        double(p[2]) - q[2] };
      if (step[0] * step[0] + step[1] * step[1] + step[2] * step[2] < short_step2)
      {
        continue;
      }
      const std::array<double, 3> d = minimum_image(step);
      for (int c = 0; c < 3; ++c)
      {
        p[c] = float(double(q[c]) + d[std::size_t(c)]);
      }
    }
  }
}

MoleculeContinuity::MoleculeContinuity(const std::vector<int>& molecule_ids)
  : Molecules(group_molecules(molecule_ids.data(), molecule_ids.size()))
{
  this->CurrentShifts.assign(3 * this->Molecules.count(), 0);
}

void MoleculeContinuity::add_frame(std::size_t frame, PointSpan<float> positions,
                                   const PeriodicBox& box)
{
  this->require_atom_count(positions);
  if (frame != this->Changes.size())
  {
    throw InvalidInput("MoleculeContinuity::add_frame: frames must be added in order (expected " +
                       std::to_string(this->Changes.size()) + ", got " + std::to_string(frame) +
                       ")");
  }
  std::vector<Change> changes;
  if (frame > 0 && box.is_set())
  {
    const std::vector<double> current = molecule_centres(this->Molecules, positions);
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(box_columns(box));
    for (std::size_t mol = 0; mol < this->Molecules.count(); ++mol)
    {
      const Eigen::Vector3d drift(this->PreviousCentroids[3 * mol] - current[3 * mol],
                                  this->PreviousCentroids[3 * mol + 1] - current[3 * mol + 1],
                                  this->PreviousCentroids[3 * mol + 2] - current[3 * mol + 2]);
      const Eigen::Vector3d fractional = lu.solve(drift);
      Change change{ std::int32_t(mol), {} };
      bool changed = false;
      for (int k = 0; k < 3; ++k)
      {
        change.shift[std::size_t(k)] = std::int32_t(std::lround(fractional[k]));
        changed =
          changed || change.shift[std::size_t(k)] != this->CurrentShifts[3 * mol + std::size_t(k)];
      }
      if (changed)
      {
        std::copy(change.shift.begin(), change.shift.end(),
                  this->CurrentShifts.begin() + long(3 * mol));
        changes.push_back(change);
      }
    }
  }
  this->Changes.push_back(std::move(changes));
  if (frame % checkpoint_interval == 0)
  {
    this->Checkpoints.push_back(this->CurrentShifts);
  }
  this->shift_atoms(this->CurrentShifts, positions, box);
  this->PreviousCentroids = molecule_centres(this->Molecules, positions);
}

std::vector<std::int32_t> MoleculeContinuity::shifts_of(std::size_t frame) const
{
  const std::size_t checkpoint = frame / checkpoint_interval;
  std::vector<std::int32_t> shifts = this->Checkpoints[checkpoint];
  for (std::size_t f = checkpoint * checkpoint_interval + 1; f <= frame; ++f)
  {
    for (const Change& change : this->Changes[f])
    {
      std::copy(change.shift.begin(), change.shift.end(),
                shifts.begin() + long(3 * std::size_t(change.molecule)));
    }
  }
  return shifts;
}

void MoleculeContinuity::apply(std::size_t frame, PointSpan<float> positions,
                               const PeriodicBox& box) const
{
  this->require_atom_count(positions);
  if (frame >= this->Changes.size())
  {
    throw InvalidInput("MoleculeContinuity::apply: frame " + std::to_string(frame) +
                       " has not been added");
  }
  this->shift_atoms(this->shifts_of(frame), positions, box);
}

void MoleculeContinuity::require_atom_count(PointSpan<const float> positions) const
{
  if (positions.size() != this->Molecules.of_atom.size())
  {
    throw InvalidInput("MoleculeContinuity tracks " +
                       std::to_string(this->Molecules.of_atom.size()) + " atoms; got " +
                       std::to_string(positions.size()) + " positions");
  }
}

void MoleculeContinuity::shift_atoms(const std::vector<std::int32_t>& shifts,
                                     PointSpan<float> positions, const PeriodicBox& box) const
{
  if (!box.is_set())
  {
    return;
  }
  // One offset per molecule; the molecules that kept their image (nearly all) are skipped.
  for (std::size_t mol = 0; mol < this->Molecules.count(); ++mol)
  {
    const std::int32_t* shift = shifts.data() + 3 * mol;
    if (shift[0] == 0 && shift[1] == 0 && shift[2] == 0)
    {
      continue;
    }
    double offset[3] = { 0, 0, 0 };
    for (std::size_t k = 0; k < 3; ++k)
    {
      for (std::size_t v = 0; v < 3; ++v)
      {
        offset[k] += double(shift[v]) * box.vectors[v][k];
      }
    }
    for (const std::uint32_t atom : this->Molecules.atoms_of(mol))
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        positions[atom][k] = float(positions[atom][k] + offset[k]);
      }
    }
  }
}

std::vector<std::array<double, 3>> assembly_shifts(PointSpan<const double> centres,
                                                   const PeriodicBox& box)
{
  const std::size_t count = centres.size();
  std::vector<std::array<double, 3>> shifts(count, { 0, 0, 0 });
  if (!box.is_set() || count == 0)
  {
    return shifts;
  }
  // Cartesian = M^T f with the box vectors as the rows of M.
  Eigen::Matrix3d cell;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      cell(c, r) = box.vectors[r][c];
    }
  }
  const Eigen::Matrix3d to_fractional = cell.inverse();
  std::vector<Eigen::Vector3d> fractional(count);
  double sines[3] = { 0, 0, 0 };
  double cosines[3] = { 0, 0, 0 };
  constexpr double turn = 2 * 3.14159265358979323846;
  for (std::size_t m = 0; m < count; ++m)
  {
    fractional[m] = to_fractional * Eigen::Vector3d(centres[m][0], centres[m][1], centres[m][2]);
    for (int d = 0; d < 3; ++d)
    {
      sines[d] += std::sin(turn * fractional[m][d]);
      cosines[d] += std::cos(turn * fractional[m][d]);
    }
  }
  for (int d = 0; d < 3; ++d)
  {
    // An assembly spread over (nearly) the whole period, such as a flat membrane that crosses
    // the box, has no middle along that axis: it stays as it is.
    const double resultant = std::hypot(sines[d], cosines[d]) / double(count);
    if (resultant < 0.25)
    {
      continue;
    }
    const double middle = std::atan2(sines[d], cosines[d]) / turn;
    std::vector<long> images(count);
    std::map<long, std::size_t> votes;
    for (std::size_t m = 0; m < count; ++m)
    {
      images[m] = std::lround(middle - fractional[m][d]);
      ++votes[images[m]];
    }
    // The largest group stays where it is; the others join it.
    const long staying =
      std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
        return a.second < b.second;
      })->first;
    for (std::size_t m = 0; m < count; ++m)
    {
      for (int c = 0; c < 3; ++c)
      {
        shifts[m][c] += double(images[m] - staying) * box.vectors[d][c];
      }
    }
  }
  return shifts;
}

} // namespace mesolens
