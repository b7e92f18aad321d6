// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/depth_pyramid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

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
                      int height, ScreenFootprint& footprint)
{
  const double* p = view.view_to_clip;
  double c[4];
  transform(view.model_to_view, centre, c);
  const double r = radius * view.view_per_model;
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

bool DepthPyramid::Hidden(const ScreenFootprint& footprint) const
{
  if (this->Levels.empty())
  {
    return false;
  }
  const int width = this->Sizes[0][0];
  const int height = this->Sizes[0][1];
  // Only pixels whose centres lie inside the outline get fragments (the impostors discard the
  // rest), so only those under the rectangle count; parts outside the image are not drawn.
  constexpr double slack = 1e-3; // pixels: rounding between this and the GPU
  int i0 = std::max(0, static_cast<int>(std::ceil(footprint.x0 - 0.5 - slack)));
  int j0 = std::max(0, static_cast<int>(std::ceil(footprint.y0 - 0.5 - slack)));
  int i1 = std::min(width - 1, static_cast<int>(std::floor(footprint.x1 - 0.5 + slack)));
  int j1 = std::min(height - 1, static_cast<int>(std::floor(footprint.y1 - 0.5 + slack)));
  if (i0 > i1 || j0 > j1)
  {
    return true; // no pixel of the image to draw
  }
  // Up to 8 x 8 pixels are read one by one; larger rectangles at the level where they span at
  // most 4 x 4 texels.
  std::size_t level = 0;
  if (i1 - i0 >= 8 || j1 - j0 >= 8)
  {
    while (level + 1 < this->Levels.size() && (i1 - i0 > 3 || j1 - j0 > 3))
    {
      i0 >>= 1;
      i1 >>= 1;
      j0 >>= 1;
      j1 >>= 1;
      ++level;
    }
  }
  const std::vector<float>& texels = this->Levels[level];
  const int w = this->Sizes[level][0];
  float farthest = 0;
  for (int j = j0; j <= j1; ++j)
  {
    for (int i = i0; i <= i1; ++i)
    {
      farthest = std::max(farthest, texels[std::size_t(j) * w + i]);
    }
  }
  return footprint.depth > double(farthest) + depth_margin;
}

CellVisibility test_atom_visibility(const DepthPyramid& pyramid, const ViewTransform& view,
                                    const float* slot_xyz, const std::uint8_t* element_of_slot,
                                    std::size_t element_stride, const float* radius_of_element,
                                    const AtomCells& cells, const std::vector<float>& boxes,
                                    const std::vector<CellInView>& in_view, double padding,
                                    std::vector<std::uint8_t>& flags,
                                    const ParallelFor& parallel_for)
{
  const std::size_t cell_count = cells.cell_count();
  CellVisibility result;
  result.seen.assign(cell_count, 0);
  result.newly_seen.assign(cell_count, 0);
  flags.resize(cells.atom_of_slot.size(), 0);
  const int width = pyramid.Width();
  const int height = pyramid.Height();
  const double* model_to_clip = view.model_to_clip;
  std::atomic<std::size_t> drawn_first_count{ 0 };
  std::atomic<std::size_t> newly_seen_count{ 0 };
  run_parallel(parallel_for, in_view.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const std::uint32_t cell = in_view[k].cell;
      const std::uint32_t first = cells.cell_start[cell];
      const std::uint32_t last = cells.cell_start[cell + 1];
      // 0: the whole cell hidden; 1: test each atom; 2: every atom visible.
      int mode = 2;
      if (!in_view[k].must_draw)
      {
        const float* box = boxes.data() + 6 * std::size_t(cell);
        const double low[3] = { box[0] - padding, box[1] - padding, box[2] - padding };
        const double high[3] = { box[3] + padding, box[4] + padding, box[5] + padding };
        ScreenFootprint footprint;
        if (box_footprint(low, high, model_to_clip, width, height, footprint))
        {
          mode = pyramid.Hidden(footprint) ? 0 : 1;
        }
      }
      bool seen = false;
      bool newly_seen = false;
      std::size_t drawn_first_here = 0;
      std::size_t newly_seen_here = 0;
      for (std::uint32_t slot = first; slot < last; ++slot)
      {
        bool visible = mode == 2;
        if (mode == 1)
        {
          const float* p = slot_xyz + 3 * std::size_t(slot);
          const double r = radius_of_element[element_of_slot[slot * element_stride]];
          const double position[3] = { p[0], p[1], p[2] };
          ScreenFootprint footprint;
          visible = !sphere_footprint(position, r, view, width, height, footprint) ||
            !pyramid.Hidden(footprint);
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
      std::fill(flags.begin() + cells.cell_start[cell], flags.begin() + cells.cell_start[cell + 1],
                std::uint8_t(0));
    }
  }
  return result;
}

} // namespace mesolens
