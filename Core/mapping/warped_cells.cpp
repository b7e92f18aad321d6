// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/warped_cells.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/polynomial_warp.h"
#include "mesolens/mapping/warp_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace mesolens {
namespace {

/// Writes `box` as floats rounded outward: the float box holds the double one.
void store_outward(const Box& box, float* out)
{
  for (std::size_t d = 0; d < 3; ++d)
  {
    const auto low = static_cast<float>(box[d]);
    const auto high = static_cast<float>(box[d + 3]);
    out[d] =
      double(low) > box[d] ? std::nextafter(low, -std::numeric_limits<float>::infinity()) : low;
    out[d + 3] = double(high) < box[d + 3]
      ? std::nextafter(high, std::numeric_limits<float>::infinity())
      : high;
  }
}

Box empty_box()
{
  constexpr double big = std::numeric_limits<double>::max();
  return { big, big, big, -big, -big, -big };
}

void grow(Box& box, const double x[3])
{
  for (std::size_t d = 0; d < 3; ++d)
  {
    box[d] = std::min(box[d], x[d]);
    box[d + 3] = std::max(box[d + 3], x[d]);
  }
}

/// A molecule's part of a cell: its index among tile 0's instances and the box of its atoms.
struct MoleculeInCell
{
  std::size_t molecule = 0;
  Box box = empty_box();
};

/// Per cell, the boxes of the molecules it holds (in order of first appearance).
std::vector<std::vector<MoleculeInCell>> molecules_in_cells(
  const AtomCells& cells, PointSpan<const float> slot_xyz,
  const std::vector<unsigned short>& molecule_of_slot, std::size_t molecules)
{
  std::vector<std::vector<MoleculeInCell>> parts(cells.cell_count());
  for (std::size_t cell = 0; cell < parts.size(); ++cell)
  {
    for (std::uint32_t slot = cells.cell_start[cell]; slot < cells.cell_start[cell + 1]; ++slot)
    {
      const std::size_t molecule = molecule_of_slot[slot];
      if (molecule >= molecules)
      {
        throw InvalidInput("warped_cell_boxes: atom slot " + std::to_string(slot) +
                           " belongs to molecule " + std::to_string(molecule) + " of " +
                           std::to_string(molecules));
      }
      auto found = std::find_if(parts[cell].begin(), parts[cell].end(),
                                [&](const MoleculeInCell& m) { return m.molecule == molecule; });
      if (found == parts[cell].end())
      {
        parts[cell].push_back({ molecule, empty_box() });
        found = parts[cell].end() - 1;
      }
      const float* p = slot_xyz[slot];
      const double x[3] = { p[0], p[1], p[2] };
      grow(found->box, x);
    }
  }
  return parts;
}

/// Rows: the unit axes of a frame whose first axis is along `a`, whose third is normal to `a`
/// and `b`; the identity where they are degenerate.
using Rotation = std::array<std::array<double, 3>, 3>;
Rotation surface_frame(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  auto norm = [](const std::array<double, 3>& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  auto cross = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                  u[0] * v[1] - u[1] * v[0] };
  };
  const std::array<double, 3> normal = cross(a, b);
  const double a_length = norm(a);
  const double normal_length = norm(normal);
  if (!(a_length > 0) || !(normal_length > 1e-12 * a_length * norm(b)) ||
      !std::isfinite(normal_length))
  {
    return { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } };
  }
  Rotation rotation{};
  for (std::size_t d = 0; d < 3; ++d)
  {
    rotation[0][d] = a[d] / a_length;
    rotation[2][d] = normal[d] / normal_length;
  }
  rotation[1] = cross(rotation[2], rotation[0]);
  return rotation;
}

} // namespace

WarpedCellBoxes warped_cell_boxes(const MembraneWarp& warp, const AtomCells& cells,
                                  const std::vector<float>& cell_boxes,
                                  PointSpan<const float> slot_xyz,
                                  const std::vector<unsigned short>& molecule_of_slot,
                                  const ParallelFor& parallel_for)
{
  const std::size_t cell_count = cells.cell_count();
  const std::size_t tiles = warp.tile_count();
  if (cell_boxes.size() != 6 * cell_count)
  {
    throw InvalidInput("warped_cell_boxes: " + std::to_string(cell_boxes.size()) +
                       " box values for " + std::to_string(cell_count) + " cells");
  }
  if (warp.method != MappingMethod::Polynomial && warp.method != MappingMethod::MoleculeInstancing)
  {
    throw InvalidInput("warped_cell_boxes: only the polynomial and instancing warps are drawn "
                       "from the patch");
  }
  const bool polynomial = warp.method == MappingMethod::Polynomial;
  const std::size_t slots = cells.atom_of_slot.size();
  if (!polynomial && (slot_xyz.size() != slots || molecule_of_slot.size() != slots))
  {
    throw InvalidInput("warped_cell_boxes: " + std::to_string(slot_xyz.size()) + " positions and " +
                       std::to_string(molecule_of_slot.size()) + " molecule indices for " +
                       std::to_string(slots) + " atoms");
  }
  const std::vector<std::size_t> first =
    polynomial ? polynomial_first_pieces(warp) : std::vector<std::size_t>{};
  const std::size_t molecules = polynomial ? 0 : molecules_per_tile(warp);
  const auto parts = polynomial ? std::vector<std::vector<MoleculeInCell>>{}
                                : molecules_in_cells(cells, slot_xyz, molecule_of_slot, molecules);
  const MembranePatch patch = warp.frame();

  WarpedCellBoxes result;
  result.frames.resize(12 * tiles);
  result.local.resize(6 * tiles * cell_count);
  result.world.resize(6 * tiles * cell_count);
  run_parallel(parallel_for, tiles, [&](std::size_t begin, std::size_t end) {
    std::vector<double> local_warp;
    for (std::size_t tile = begin; tile < end; ++tile)
    {
      // The tile's frame: its axes along the surface (first the patch's a direction) and its
      // normal, at its centre; rows of the rotation R (mesh to local) and the origin o.
      std::array<double, 3> along_a{}, along_b{}, origin{};
      const int splits =
        polynomial && !warp.polynomial_splits.empty() ? warp.polynomial_splits[tile] : 1;
      if (polynomial)
      {
        const double* centre_piece = warp.polynomial_coefficients.data() +
          3 * quadratic_terms * (first[tile] + std::size_t((splits / 2) * splits + splits / 2));
        for (std::size_t d = 0; d < 3; ++d)
        {
          origin[d] = centre_piece[quadratic_terms * d];
          along_a[d] = centre_piece[quadratic_terms * d + 1];
          along_b[d] = centre_piece[quadratic_terms * d + 2];
        }
      }
      else
      {
        const double* m = warp.instance_matrices.data() + 16 * tile * molecules;
        for (std::size_t d = 0; d < 3; ++d)
        {
          origin[d] = m[4 * d + 3];
          along_a[d] = m[4 * d];
          along_b[d] = m[4 * d + 1];
        }
      }
      const Rotation rotation = surface_frame(along_a, along_b);
      double* frame = result.frames.data() + 12 * tile;
      for (std::size_t r = 0; r < 3; ++r)
      {
        for (std::size_t c = 0; c < 3; ++c)
        {
          frame[4 * r + c] = rotation[c][r]; // local to mesh: the transpose
        }
        frame[4 * r + 3] = origin[r];
      }
      auto to_local = [&](const double x[3], double l[3]) {
        for (std::size_t r = 0; r < 3; ++r)
        {
          l[r] = rotation[r][0] * (x[0] - origin[0]) + rotation[r][1] * (x[1] - origin[1]) +
            rotation[r][2] * (x[2] - origin[2]);
        }
      };
      if (polynomial)
      {
        // The tile's pieces in local coordinates: every coefficient vector rotated, the
        // constant one also shifted.
        const std::size_t values = 3 * quadratic_terms * std::size_t(splits * splits);
        const double* global =
          warp.polynomial_coefficients.data() + 3 * quadratic_terms * first[tile];
        local_warp.assign(values, 0.0);
        for (std::size_t piece = 0; piece < std::size_t(splits * splits); ++piece)
        {
          const double* w = global + 3 * quadratic_terms * piece;
          double* l = local_warp.data() + 3 * quadratic_terms * piece;
          for (std::size_t k = 0; k < quadratic_terms; ++k)
          {
            const double c[3] = { w[k] - (k == 0 ? origin[0] : 0.0),
                                  w[quadratic_terms + k] - (k == 0 ? origin[1] : 0.0),
                                  w[2 * quadratic_terms + k] - (k == 0 ? origin[2] : 0.0) };
            for (std::size_t r = 0; r < 3; ++r)
            {
              l[quadratic_terms * r + k] =
                rotation[r][0] * c[0] + rotation[r][1] * c[1] + rotation[r][2] * c[2];
            }
          }
        }
      }
      for (std::size_t cell = 0; cell < cell_count; ++cell)
      {
        const std::size_t k = tile * cell_count + cell;
        Box bounds = empty_box();
        if (polynomial)
        {
          const float* box = cell_boxes.data() + 6 * cell;
          bounds = warped_box(patch, warp.layer_half_thickness, splits, local_warp.data(),
                              { box[0], box[1], box[2], box[3], box[4], box[5] });
        }
        else
        {
          for (const MoleculeInCell& part : parts[cell])
          {
            const double* m =
              warp.instance_matrices.data() + 16 * (tile * molecules + part.molecule);
            for (int corner = 0; corner < 8; ++corner)
            {
              const double p[3] = { part.box[(corner & 1) ? 3 : 0], part.box[(corner & 2) ? 4 : 1],
                                    part.box[(corner & 4) ? 5 : 2] };
              double x[3], l[3];
              for (std::size_t r = 0; r < 3; ++r)
              {
                x[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
              }
              to_local(x, l);
              grow(bounds, l);
            }
          }
        }
        store_outward(bounds, result.local.data() + 6 * k);
        // The world box of the local one: its corners through the frame.
        const float* local = result.local.data() + 6 * k;
        Box world = empty_box();
        for (int corner = 0; corner < 8; ++corner)
        {
          const double l[3] = { local[(corner & 1) ? 3 : 0], local[(corner & 2) ? 4 : 1],
                                local[(corner & 4) ? 5 : 2] };
          double x[3];
          for (std::size_t r = 0; r < 3; ++r)
          {
            x[r] = frame[4 * r] * l[0] + frame[4 * r + 1] * l[1] + frame[4 * r + 2] * l[2] +
              frame[4 * r + 3];
          }
          grow(world, x);
        }
        store_outward(world, result.world.data() + 6 * k);
      }
    }
  });
  return result;
}

WarpedCellAtoms::WarpedCellAtoms(const MembraneWarp& warp, const AtomCells& cells,
                                 const std::vector<float>& cell_boxes,
                                 PointSpan<const float> slot_xyz,
                                 const std::vector<unsigned short>& molecule_of_slot,
                                 const std::vector<std::uint8_t>& element_of_slot,
                                 std::size_t element_stride,
                                 const std::vector<float>& radius_of_element,
                                 double relative_margin, const ParallelFor& parallel_for)
  : Warp(warp)
  , Cells(cells)
  , SlotXYZ(slot_xyz)
  , MoleculeOfSlot(molecule_of_slot)
  , ElementOfSlot(element_of_slot)
  , ElementStride(element_stride)
  , RadiusOfElement(radius_of_element)
{
  check_drawable(warp);
  const std::size_t slots = cells.atom_of_slot.size();
  if (slot_xyz.size() != slots)
  {
    throw InvalidInput("WarpedCellAtoms: " + std::to_string(slot_xyz.size()) + " positions for " +
                       std::to_string(slots) + " atoms");
  }
  if (double(slots) * double(warp.tile_count()) > double(std::numeric_limits<std::uint32_t>::max()))
  {
    throw InvalidInput("WarpedCellAtoms: " + std::to_string(warp.tile_count()) + " tiles of " +
                       std::to_string(slots) + " atoms exceed 2^32 - 1 slots");
  }
  this->Boxes =
    warped_cell_boxes(warp, cells, cell_boxes, slot_xyz, molecule_of_slot, parallel_for);
  float largest = 0;
  for (const float value : this->Boxes.world)
  {
    largest = std::max(largest, std::abs(value));
  }
  this->Margin = relative_margin * largest;
  if (warp.method == MappingMethod::Polynomial)
  {
    this->FirstPiece = polynomial_first_pieces(warp);
    const MembranePatch frame = warp.frame();
    this->LocalCoordinates.resize(3 * slots);
    for (std::size_t slot = 0; slot < slots; ++slot)
    {
      const auto local = polynomial_coordinates(frame, warp.layer_half_thickness, slot_xyz[slot]);
      std::copy(local.begin(), local.end(), this->LocalCoordinates.begin() + 3 * slot);
    }
  }
  else
  {
    this->Molecules = molecules_per_tile(warp);
    if (molecule_of_slot.size() != slots)
    {
      throw InvalidInput("WarpedCellAtoms: " + std::to_string(molecule_of_slot.size()) +
                         " molecule indices for " + std::to_string(slots) + " atoms");
    }
    for (const unsigned short molecule : molecule_of_slot)
    {
      if (molecule >= this->Molecules)
      {
        throw InvalidInput("WarpedCellAtoms: molecule index " + std::to_string(molecule) + " of " +
                           std::to_string(this->Molecules));
      }
    }
  }
}

std::size_t WarpedCellAtoms::cell_count() const
{
  return this->Warp.tile_count() * this->Cells.cell_count();
}

std::uint32_t WarpedCellAtoms::first_slot(std::size_t cell) const
{
  const std::size_t cells = this->Cells.cell_count();
  const std::size_t atoms = this->Cells.atom_of_slot.size();
  return static_cast<std::uint32_t>(cell / cells * atoms + this->Cells.cell_start[cell % cells]);
}

void WarpedCellAtoms::load(std::size_t cell, std::vector<float>& xyz,
                           std::vector<float>& radii) const
{
  const std::size_t cells = this->Cells.cell_count();
  const std::size_t tile = cell / cells;
  const std::uint32_t first = this->Cells.cell_start[cell % cells];
  const std::uint32_t end = this->Cells.cell_start[cell % cells + 1];
  xyz.resize(3 * std::size_t(end - first));
  radii.resize(end - first);
  const bool polynomial = this->Warp.method == MappingMethod::Polynomial;
  const int splits =
    !polynomial || this->Warp.polynomial_splits.empty() ? 1 : this->Warp.polynomial_splits[tile];
  const double* tile_warp = polynomial
    ? this->Warp.polynomial_coefficients.data() + 3 * quadratic_terms * this->FirstPiece[tile]
    : nullptr;
  for (std::uint32_t slot = first; slot < end; ++slot)
  {
    radii[slot - first] =
      this->RadiusOfElement[this->ElementOfSlot[std::size_t(slot) * this->ElementStride]] +
      static_cast<float>(this->Margin);
  }
  // The monomials are computed here, not kept: a table of them cost 80 bytes per patch atom per
  // piece count, several times the GPU buffers, for no faster a test.
  const double* local = this->LocalCoordinates.data();
  for (std::uint32_t slot = first; slot < end; ++slot)
  {
    std::array<double, 3> x{ 0, 0, 0 };
    if (polynomial)
    {
      // As evaluate_tile_polynomial, from the tile-independent coordinates.
      double s = local[3 * slot];
      double t = local[3 * slot + 1];
      const double* warp =
        tile_warp + 3 * quadratic_terms * std::size_t(polynomial_piece(splits, s, t));
      const auto monomials = quadratic_monomials(s, t, local[3 * slot + 2]);
      for (std::size_t d = 0; d < 3; ++d)
      {
        for (std::size_t k = 0; k < quadratic_terms; ++k)
        {
          x[d] += warp[quadratic_terms * d + k] * monomials[k];
        }
      }
    }
    else
    {
      const float* p = this->SlotXYZ[slot];
      const double* m = this->Warp.instance_matrices.data() +
        16 * (tile * this->Molecules + this->MoleculeOfSlot[slot]);
      for (std::size_t r = 0; r < 3; ++r)
      {
        x[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      }
    }
    for (std::size_t d = 0; d < 3; ++d)
    {
      xyz[3 * std::size_t(slot - first) + d] = static_cast<float>(x[d]);
    }
  }
}

bool WarpedCellAtoms::cell_footprint(std::size_t cell, const std::vector<float>&, double padding,
                                     const ViewTransform& view, int width, int height,
                                     ScreenFootprint& footprint) const
{
  // Model to clip times the tile's local to mesh map.
  const double* frame = this->Boxes.frames.data() + 12 * (cell / this->Cells.cell_count());
  const double* m = view.model_to_clip;
  double local_to_clip[16];
  for (std::size_t r = 0; r < 4; ++r)
  {
    for (std::size_t c = 0; c < 4; ++c)
    {
      local_to_clip[4 * r + c] = m[4 * r] * frame[c] + m[4 * r + 1] * frame[4 + c] +
        m[4 * r + 2] * frame[8 + c] + (c == 3 ? m[4 * r + 3] : 0.0);
    }
  }
  const float* box = this->Boxes.local.data() + 6 * cell;
  const double low[3] = { box[0] - padding, box[1] - padding, box[2] - padding };
  const double high[3] = { box[3] + padding, box[4] + padding, box[5] + padding };
  return box_footprint(low, high, local_to_clip, width, height, footprint);
}

} // namespace mesolens
