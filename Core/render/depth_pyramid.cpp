// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/depth_pyramid.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <string>

namespace mesolens {
namespace {

/// Depths closer than this to the farthest depth drawn count as visible: the depth buffer has
/// 24 bits, the footprint is computed in double.
constexpr double depth_margin = 1.0 / (1 << 20);

/// The footprint of the 8 points centre ± ex ± ey ± ez, all in clip coordinates.
bool corners_footprint(const double centre[4], const double ex[4], const double ey[4],
                       const double ez[4], int width, int height, ScreenFootprint& footprint)
{
  footprint = { 1e300, 1e300, -1e300, -1e300, 1e300 };
  for (int k = 0; k < 8; ++k)
  {
    const double sx = (k & 1) ? 1.0 : -1.0;
    const double sy = (k & 2) ? 1.0 : -1.0;
    const double sz = (k & 4) ? 1.0 : -1.0;
    double clip[4];
    for (int r = 0; r < 4; ++r)
    {
      clip[r] = centre[r] + sx * ex[r] + sy * ey[r] + sz * ez[r];
    }
    if (!(clip[3] > 0) || clip[2] < -clip[3])
    {
      return false;
    }
    const double x = (clip[0] / clip[3] + 1.0) * 0.5 * width;
    const double y = (clip[1] / clip[3] + 1.0) * 0.5 * height;
    footprint.x0 = std::min(footprint.x0, x);
    footprint.x1 = std::max(footprint.x1, x);
    footprint.y0 = std::min(footprint.y0, y);
    footprint.y1 = std::max(footprint.y1, y);
    footprint.depth = std::min(footprint.depth, (clip[2] / clip[3] + 1.0) * 0.5);
  }
  return true;
}

/// Column c of the row-major matrix times s.
void scaled_column(const double m[16], int c, double s, double out[4])
{
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[4 * r + c] * s;
  }
}

void transform(const double m[16], const double p[3], double out[4])
{
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  }
}
/// floor and ceil clamped to [-2^30, 2^30], inline (the library calls dominate otherwise).
int floor_int(double x)
{
  x = std::clamp(x, -1073741824.0, 1073741824.0);
  const int truncated = static_cast<int>(x);
  return truncated > x ? truncated - 1 : truncated;
}

int ceil_int(double x)
{
  return -floor_int(-x);
}

/// A rectangle of texels of one level, inclusive.
struct TexelRange
{
  int i0 = 0;
  int j0 = 0;
  int i1 = 0;
  int j1 = 0;

  /// Halves it until it spans fewer than `most` texels both ways (or `levels` run out); the
  /// level reached.
  std::size_t Coarsen(int most, std::size_t levels)
  {
    std::size_t level = 0;
    while (level + 1 < levels && (i1 - i0 >= most || j1 - j0 >= most))
    {
      i0 >>= 1;
      i1 >>= 1;
      j0 >>= 1;
      j1 >>= 1;
      ++level;
    }
    return level;
  }
};

/// The pixels of a width x height image whose centres lie in the footprint's rectangle: only
/// they can get fragments (the impostors discard the rest), and parts outside the image are not
/// drawn. False when there are none.
bool pixel_range(const ScreenFootprint& footprint, int width, int height, TexelRange& range)
{
  constexpr double slack = 1e-3; // pixels: rounding between this and the GPU
  range.i0 = std::max(0, ceil_int(footprint.x0 - 0.5 - slack));
  range.j0 = std::max(0, ceil_int(footprint.y0 - 0.5 - slack));
  range.i1 = std::min(width - 1, floor_int(footprint.x1 - 0.5 + slack));
  range.j1 = std::min(height - 1, floor_int(footprint.y1 - 0.5 + slack));
  return range.i0 <= range.i1 && range.j0 <= range.j1;
}
} // namespace

void ViewTransform::Complete()
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
      {
        sum += view_to_clip[4 * r + k] * model_to_view[4 * k + c];
      }
      model_to_clip[4 * r + c] = sum;
    }
  }
  const double* m = model_to_view;
  view_per_model =
    std::cbrt(std::abs(m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                       m[2] * (m[4] * m[9] - m[5] * m[8])));
}

bool sphere_footprint(const double centre[3], double radius, const ViewTransform& view, int width,
                      int height, ScreenFootprint& footprint, EyeSphere* eye)
{
  const double* p = view.view_to_clip;
  double c[4];
  transform(view.model_to_view, centre, c);
  const double r = radius * view.view_per_model;
  if (eye)
  {
    std::copy(c, c + 3, eye->centre);
    eye->radius = r;
  }
  // The nearest point of the sphere in depth: its eye-space z is the centre's plus r.
  const double nearest[3] = { c[0], c[1], c[2] + r };
  double clip[4];
  transform(p, nearest, clip);
  if (!(clip[3] > 0) || clip[2] < -clip[3])
  {
    return false;
  }
  footprint.depth = (clip[2] / clip[3] + 1.0) * 0.5;
  double ndc[2][2]; // [axis][low, high]
  const bool perspective = p[14] != 0;
  if (!perspective)
  {
    // Affine: the outline spans r times the row's length around the centre.
    double centre_clip[4];
    transform(p, c, centre_clip);
    for (int a = 0; a < 2; ++a)
    {
      const double reach =
        r * (std::abs(p[4 * a]) + std::abs(p[4 * a + 1]) + std::abs(p[4 * a + 2]));
      ndc[a][0] = (centre_clip[a] - reach) / centre_clip[3];
      ndc[a][1] = (centre_clip[a] + reach) / centre_clip[3];
    }
  }
  else
  {
    // w = -z: in each of the planes xz and yz, the tangents from the eye to the circle bound
    // u = x / -z within tan(theta ± alpha), theta the centre's angle, sin(alpha) = r / d.
    // VTK's projections have clip x = p0 x + p2 z (and y alike): ndc x = p0 u - p2. Other
    // forms get no footprint (and count as visible).
    if (p[1] != 0 || p[3] != 0 || p[4] != 0 || p[7] != 0 || p[12] != 0 || p[13] != 0 ||
        p[14] != -1 || p[15] != 0)
    {
      return false;
    }
    for (int a = 0; a < 2; ++a)
    {
      const double lateral = c[a];
      const double ahead = -c[2];
      const double tangent2 = lateral * lateral + ahead * ahead - r * r;
      if (!(ahead > r) || !(tangent2 > 0))
      {
        return false;
      }
      const double tan_theta = lateral / ahead;
      const double tan_alpha = r / std::sqrt(tangent2);
      const double below = 1.0 + tan_theta * tan_alpha;
      const double above = 1.0 - tan_theta * tan_alpha;
      if (!(below > 0) || !(above > 0))
      {
        return false; // the outline reaches 90 degrees off the view axis
      }
      const double u_low = (tan_theta - tan_alpha) / below;
      const double u_high = (tan_theta + tan_alpha) / above;
      const double scale = p[5 * a];
      const double shift = -p[4 * a + 2];
      ndc[a][0] = std::min(scale * u_low, scale * u_high) + shift;
      ndc[a][1] = std::max(scale * u_low, scale * u_high) + shift;
    }
  }
  footprint.x0 = (ndc[0][0] + 1.0) * 0.5 * width;
  footprint.x1 = (ndc[0][1] + 1.0) * 0.5 * width;
  footprint.y0 = (ndc[1][0] + 1.0) * 0.5 * height;
  footprint.y1 = (ndc[1][1] + 1.0) * 0.5 * height;
  return true;
}

bool box_footprint(const double low[3], const double high[3], const double model_to_clip[16],
                   int width, int height, ScreenFootprint& footprint)
{
  const double centre[3] = { 0.5 * (low[0] + high[0]), 0.5 * (low[1] + high[1]),
                             0.5 * (low[2] + high[2]) };
  double c[4];
  double ex[4];
  double ey[4];
  double ez[4];
  transform(model_to_clip, centre, c);
  scaled_column(model_to_clip, 0, 0.5 * (high[0] - low[0]), ex);
  scaled_column(model_to_clip, 1, 0.5 * (high[1] - low[1]), ey);
  scaled_column(model_to_clip, 2, 0.5 * (high[2] - low[2]), ez);
  return corners_footprint(c, ex, ey, ez, width, height, footprint);
}

void DepthPyramid::Build(const float* depth, int width, int height)
{
  this->Levels.clear();
  this->Sizes.clear();
  if (!depth || width <= 0 || height <= 0)
  {
    return;
  }
  this->Levels.emplace_back(depth, depth + std::size_t(width) * std::size_t(height));
  this->Sizes.push_back({ width, height });
  while (this->Sizes.back()[0] > 1 || this->Sizes.back()[1] > 1)
  {
    const auto [w, h] = this->Sizes.back();
    const int nw = (w + 1) / 2;
    const int nh = (h + 1) / 2;
    const std::vector<float>& below = this->Levels.back();
    std::vector<float> level(std::size_t(nw) * std::size_t(nh));
    for (int j = 0; j < nh; ++j)
    {
      for (int i = 0; i < nw; ++i)
      {
        const int i0 = 2 * i;
        const int i1 = std::min(2 * i + 1, w - 1);
        const int j0 = 2 * j;
        const int j1 = std::min(2 * j + 1, h - 1);
        level[std::size_t(j) * nw + i] =
          std::max({ below[std::size_t(j0) * w + i0], below[std::size_t(j0) * w + i1],
                     below[std::size_t(j1) * w + i0], below[std::size_t(j1) * w + i1] });
      }
    }
    this->Levels.push_back(std::move(level));
    this->Sizes.push_back({ nw, nh });
  }
}

bool DepthPyramid::Covered(std::size_t level, int i0, int j0, int i1, int j1,
                           double visible_from) const
{
  const std::vector<float>& texels = this->Levels[level];
  const int w = this->Sizes[level][0];
  for (int j = j0; j <= j1; ++j)
  {
    const float* row = texels.data() + std::size_t(j) * w;
    for (int i = i0; i <= i1; ++i)
    {
      if (double(row[i]) >= visible_from)
      {
        return false;
      }
    }
  }
  return true;
}

int DepthPyramid::HiddenCoarse(const ScreenFootprint& footprint, int pixels[4]) const
{
  if (this->Levels.empty())
  {
    return 0;
  }
  TexelRange range;
  if (!pixel_range(footprint, this->Sizes[0][0], this->Sizes[0][1], range))
  {
    return 1; // no pixel of the image to draw
  }
  pixels[0] = range.i0;
  pixels[1] = range.j0;
  pixels[2] = range.i1;
  pixels[3] = range.j1;
  // The level where the rectangle spans at most 2 x 2 texels: most hidden atoms end there.
  const std::size_t level = range.Coarsen(2, this->Levels.size());
  if (this->Covered(level, range.i0, range.j0, range.i1, range.j1, footprint.depth - depth_margin))
  {
    return 1;
  }
  return level == 0 ? 0 : -1;
}

bool DepthPyramid::Hidden(const ScreenFootprint& footprint, int most_texels) const
{
  int pixels[4];
  const int coarse = this->HiddenCoarse(footprint, pixels);
  if (coarse >= 0)
  {
    return coarse == 1;
  }
  // Up to (2 most_texels)^2 pixels one by one, or most_texels^2 texels of a coarser level.
  TexelRange range{ pixels[0], pixels[1], pixels[2], pixels[3] };
  const double visible_from = footprint.depth - depth_margin;
  if (range.i1 - range.i0 < 2 * most_texels && range.j1 - range.j0 < 2 * most_texels)
  {
    return this->Covered(0, range.i0, range.j0, range.i1, range.j1, visible_from);
  }
  const std::size_t level = range.Coarsen(most_texels, this->Levels.size());
  return this->Covered(level, range.i0, range.j0, range.i1, range.j1, visible_from);
}

double DepthPyramid::Farthest(const ScreenFootprint& footprint, int most_texels) const
{
  if (this->Levels.empty())
  {
    return 1.0;
  }
  TexelRange range;
  if (!pixel_range(footprint, this->Sizes[0][0], this->Sizes[0][1], range))
  {
    return 0.0;
  }
  std::size_t level = 0;
  if (range.i1 - range.i0 >= 2 * most_texels || range.j1 - range.j0 >= 2 * most_texels)
  {
    level = range.Coarsen(most_texels, this->Levels.size());
  }
  const std::vector<float>& texels = this->Levels[level];
  const int w = this->Sizes[level][0];
  float farthest = 0;
  for (int j = range.j0; j <= range.j1; ++j)
  {
    for (int i = range.i0; i <= range.i1; ++i)
    {
      farthest = std::max(farthest, texels[std::size_t(j) * w + i]);
    }
  }
  return double(farthest);
}

bool DepthPyramid::SphereHidden(const ScreenFootprint& footprint, const EyeSphere& sphere,
                                const double view_to_clip[16]) const
{
  if (this->Levels.empty())
  {
    return false;
  }
  int pixels[4];
  if (this->HiddenCoarse(footprint, pixels) == 1)
  {
    return true;
  }
  const int i0 = pixels[0];
  const int j0 = pixels[1];
  const int i1 = pixels[2];
  const int j1 = pixels[3];
  if (i1 - i0 >= 16 || j1 - j0 >= 16)
  {
    return this->Hidden(footprint);
  }
  const int width = this->Sizes[0][0];
  const int height = this->Sizes[0][1];
  // The sphere shows at a pixel when the ray through its centre meets the sphere and what is
  // drawn there lies no nearer than the sphere's nearest point (a hit is never nearer).
  const double* p = view_to_clip;
  const bool perspective = p[14] != 0;
  const double* c = sphere.centre;
  // A slightly larger sphere: whatever the GPU's rounding, its pixels are among these.
  const double r = sphere.radius * (1.0 + 1e-4);
  const double visible_from = footprint.depth - depth_margin;
  const double beyond = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - r * r; // |c|² - r²
  const std::vector<float>& depth = this->Levels[0];
  for (int j = j0; j <= j1; ++j)
  {
    const double y_ndc = 2.0 * (j + 0.5) / height - 1.0;
    const float* row = depth.data() + std::size_t(j) * width;
    for (int i = i0; i <= i1; ++i)
    {
      if (double(row[i]) < visible_from)
      {
        continue; // something nearer than any point of the sphere
      }
      const double x_ndc = 2.0 * (i + 0.5) / width - 1.0;
      bool meets = false;
      if (perspective)
      {
        // The ray from the eye along d = (u, v, -1), u = x / -z (ndc x = p0 u - p2), meets the
        // sphere when (c.d)² >= (|c|² - r²) |d|², c.d > 0.
        const double u = (x_ndc + p[2]) / p[0];
        const double v = (y_ndc + p[6]) / p[5];
        const double along = u * c[0] + v * c[1] - c[2];
        meets = along > 0 && along * along >= beyond * (u * u + v * v + 1.0);
      }
      else
      {
        // Parallel rays down -z through (x, y): ndc x = p0 x + p3.
        const double x = (x_ndc - p[3]) / p[0] - c[0];
        const double y = (y_ndc - p[7]) / p[5] - c[1];
        meets = x * x + y * y <= r * r;
      }
      if (meets)
      {
        return false;
      }
    }
  }
  return true;
}

bool CellAtoms::cell_footprint(std::size_t cell, const std::vector<float>& boxes, double padding,
                               const ViewTransform& view, int width, int height,
                               ScreenFootprint& footprint) const
{
  const float* box = boxes.data() + 6 * cell;
  const double low[3] = { box[0] - padding, box[1] - padding, box[2] - padding };
  const double high[3] = { box[3] + padding, box[4] + padding, box[5] + padding };
  return box_footprint(low, high, view.model_to_clip, width, height, footprint);
}

StoredCellAtoms::StoredCellAtoms(PointSpan<const float> slot_xyz,
                                 const std::uint8_t* element_of_slot, std::size_t element_stride,
                                 const float* radius_of_element, const AtomCells& cells)
  : SlotXYZ(slot_xyz)
  , ElementOfSlot(element_of_slot)
  , ElementStride(element_stride)
  , RadiusOfElement(radius_of_element)
  , Cells(cells)
{
}

std::size_t StoredCellAtoms::cell_count() const
{
  return this->Cells.cell_count();
}

std::uint32_t StoredCellAtoms::first_slot(std::size_t cell) const
{
  return this->Cells.cell_start[cell];
}

void StoredCellAtoms::load(std::size_t cell, std::vector<float>& xyz,
                           std::vector<float>& radii) const
{
  const std::uint32_t first = this->Cells.cell_start[cell];
  const std::uint32_t end = this->Cells.cell_start[cell + 1];
  xyz.assign(this->SlotXYZ[first], this->SlotXYZ[first] + 3 * std::size_t(end - first));
  radii.resize(end - first);
  for (std::uint32_t slot = first; slot < end; ++slot)
  {
    radii[slot - first] =
      this->RadiusOfElement[this->ElementOfSlot[std::size_t(slot) * this->ElementStride]];
  }
}

CellVisibility test_atom_visibility(
  const DepthPyramid& pyramid, const ViewTransform& view, PointSpan<const float> slot_xyz,
  const std::uint8_t* element_of_slot, std::size_t element_stride, const float* radius_of_element,
  const AtomCells& cells, const std::vector<float>& boxes, const std::vector<CellInView>& in_view,
  double padding, std::vector<std::uint8_t>& flags, const ParallelFor& parallel_for)
{
  const StoredCellAtoms atoms(slot_xyz, element_of_slot, element_stride, radius_of_element, cells);
  return test_atom_visibility(pyramid, view, atoms, boxes, in_view, padding, flags, parallel_for);
}

CellVisibility test_atom_visibility(const DepthPyramid& pyramid, const ViewTransform& view,
                                    const CellAtoms& atoms, const std::vector<float>& boxes,
                                    const std::vector<CellInView>& in_view, double padding,
                                    std::vector<std::uint8_t>& flags,
                                    const ParallelFor& parallel_for)
{
  const std::size_t cell_count = atoms.cell_count();
  if (boxes.size() != 6 * cell_count)
  {
    throw InvalidInput("test_atom_visibility: " + std::to_string(boxes.size() / 6) + " boxes for " +
                       std::to_string(cell_count) + " cells");
  }
  CellVisibility result;
  result.seen.assign(cell_count, 0);
  result.newly_seen.assign(cell_count, 0);
  flags.resize(atoms.first_slot(cell_count), 0);
  const int width = pyramid.Width();
  const int height = pyramid.Height();
  std::atomic<std::size_t> drawn_first_count{ 0 };
  std::atomic<std::size_t> newly_seen_count{ 0 };
  run_parallel(parallel_for, in_view.size(), [&](std::size_t begin, std::size_t end) {
    std::vector<float> xyz;
    std::vector<float> radii;
    for (std::size_t k = begin; k < end; ++k)
    {
      const std::uint32_t cell = in_view[k].cell;
      const std::uint32_t first = atoms.first_slot(cell);
      const std::uint32_t last = atoms.first_slot(std::size_t(cell) + 1);
      // 0: the whole cell hidden; 1: test each atom; 2: every atom visible.
      int mode = 2;
      double cell_farthest = 1.0; // the farthest depth drawn over the cell's footprint
      if (!in_view[k].must_draw)
      {
        ScreenFootprint footprint;
        if (atoms.cell_footprint(cell, boxes, padding, view, width, height, footprint))
        {
          mode = pyramid.Hidden(footprint, 8) ? 0 : 1;
          cell_farthest = pyramid.Farthest(footprint, 8);
        }
      }
      bool seen = false;
      bool newly_seen = false;
      std::size_t drawn_first_here = 0;
      std::size_t newly_seen_here = 0;
      if (mode == 1)
      {
        atoms.load(cell, xyz, radii);
      }
      for (std::uint32_t slot = first; slot < last; ++slot)
      {
        bool visible = mode == 2;
        if (mode == 1)
        {
          const float* p = xyz.data() + 3 * std::size_t(slot - first);
          const double r = radii[slot - first];
          // Behind everything drawn over its cell's footprint: hidden, without its outline.
          const double* m = view.model_to_view;
          const double z =
            m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11] + r * view.view_per_model;
          const double* q = view.view_to_clip;
          const double w = q[14] * z + q[15];
          const bool behind =
            w > 0 && ((q[10] * z + q[11]) / w + 1.0) * 0.5 > cell_farthest + depth_margin;
          if (!behind)
          {
            const double position[3] = { p[0], p[1], p[2] };
            ScreenFootprint footprint;
            EyeSphere eye;
            visible = !sphere_footprint(position, r, view, width, height, footprint, &eye) ||
              !pyramid.SphereHidden(footprint, eye, view.view_to_clip);
          }
        }
        const bool drawn_first = (flags[slot] & SEEN) != 0;
        const bool fresh = visible && !drawn_first;
        flags[slot] = static_cast<std::uint8_t>((visible ? SEEN : 0) | (fresh ? NEWLY_SEEN : 0));
        seen = seen || visible;
        newly_seen = newly_seen || fresh;
        drawn_first_here += drawn_first ? 1 : 0;
        newly_seen_here += fresh ? 1 : 0;
      }
      drawn_first_count += drawn_first_here;
      newly_seen_count += newly_seen_here;
      result.seen[cell] = seen ? 1 : 0;
      result.newly_seen[cell] = newly_seen ? 1 : 0;
    }
  });
  result.drawn_first = drawn_first_count;
  result.drawn_after = newly_seen_count;
  // Cells out of view: nothing of theirs is drawn first next time.
  std::vector<std::uint8_t> viewed(cell_count, 0);
  for (const CellInView& cell : in_view)
  {
    viewed[cell.cell] = 1;
  }
  for (std::size_t cell = 0; cell < cell_count; ++cell)
  {
    if (!viewed[cell])
    {
      std::fill(flags.begin() + atoms.first_slot(cell), flags.begin() + atoms.first_slot(cell + 1),
                std::uint8_t(0));
    }
  }
  return result;
}

} // namespace mesolens
