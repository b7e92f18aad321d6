// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/first_occluders.h"

#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

namespace {
/// Model space is eye space; x, y in [-10, 10] fill a 200 x 200 viewport (10 pixels per unit),
/// view depth [1, 11] looking down -z.
mesolens::ViewTransform orthographic_view()
{
  mesolens::ViewTransform view{};
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  const double projection[16] = { 0.1, 0, 0, 0, 0, 0.1, 0, 0, 0, 0, -0.2, -1.2, 0, 0, 0, 1 };
  std::copy(identity, identity + 16, view.model_to_view);
  std::copy(projection, projection + 16, view.view_to_clip);
  view.Complete();
  return view;
}

/// Cells of one atom each at the centres of `boxes` (6 per cell).
struct BoxCells
{
  std::vector<float> boxes;
  std::vector<float> xyz;
  std::vector<std::uint8_t> elements;
  std::vector<float> radii{ 0.5f };
  mesolens::AtomCells cells;

  explicit BoxCells(std::vector<float> cell_boxes)
    : boxes(std::move(cell_boxes))
  {
    for (std::size_t c = 0; 6 * c < this->boxes.size(); ++c)
    {
      for (int d = 0; d < 3; ++d)
      {
        this->xyz.push_back(0.5f * (this->boxes[6 * c + d] + this->boxes[6 * c + 3 + d]));
      }
      this->elements.push_back(0);
      this->cells.atom_of_slot.push_back(std::uint32_t(c));
      this->cells.cell_start.push_back(std::uint32_t(c));
    }
    this->cells.cell_start.push_back(std::uint32_t(this->boxes.size() / 6));
  }

  mesolens::StoredCellAtoms atoms() const
  {
    return { { this->xyz.data(), this->xyz.size() / 3 },
             this->elements.data(),
             1,
             this->radii.data(),
             this->cells };
  }
};
} // namespace

TEST(FirstOccluders, CellsBehindTheNearestSurfaceWaitForTheTest)
{
  // Cell 0: a slab in front (z = -2) over x, y in [-5, 5]; cell 1 right behind it (z = -6);
  // cell 2 behind it too but reaching out beside it (x up to 9); cell 3 beside everything.
  const BoxCells input({ -5, -5, -2.5f, 5, 5,  -2,    // 0
                         -4, -4, -6.5f, 4, 4,  -6,    // 1
                         -4, -4, -8.5f, 9, 4,  -8,    // 2
                         6,  -9, -4.5f, 9, -6, -4 }); // 3
  const mesolens::ViewTransform view = orthographic_view();
  const std::vector<mesolens::CellInView> in_view =
    mesolens::cells_in_view(input.boxes, 0.0, view.model_to_clip);
  ASSERT_EQ(in_view.size(), 4u);
  const auto atoms = input.atoms();
  const std::vector<std::uint8_t> chosen =
    mesolens::first_occluders(atoms, input.boxes, in_view, 0.0, view, 200, 200);
  EXPECT_EQ(chosen, (std::vector<std::uint8_t>{ 1, 0, 1, 1 }));
  // Blocks as large as the screen: the first cell covers none whole, its centre's block stands
  // for it, and every cell after it is behind that block.
  const std::vector<std::uint8_t> coarse =
    mesolens::first_occluders(atoms, input.boxes, in_view, 0.0, view, 200, 200, 400);
  EXPECT_EQ(std::count(coarse.begin(), coarse.end(), 1), 1);
}

TEST(FirstOccluders, UnprojectableCellsAreAlwaysChosenAndBadArgumentsRefused)
{
  // Cell 1 reaches the eye's plane (z = 0 and beyond): it has no footprint.
  const BoxCells input({ -5, -5, -2.5f, 5, 5, -2, -1, -1, -3, 1, 1, 0.5f });
  const mesolens::ViewTransform view = orthographic_view();
  const std::vector<mesolens::CellInView> in_view =
    mesolens::cells_in_view(input.boxes, 0.0, view.model_to_clip);
  const auto atoms = input.atoms();
  const std::vector<std::uint8_t> chosen =
    mesolens::first_occluders(atoms, input.boxes, in_view, 0.0, view, 200, 200);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[1], 1);
  EXPECT_THROW(mesolens::first_occluders(atoms, input.boxes, in_view, 0.0, view, 200, 200, 0),
               mesolens::InvalidInput);
  const std::vector<std::uint8_t> none =
    mesolens::first_occluders(atoms, input.boxes, in_view, 0.0, view, 0, 0);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}
