// SPDX-License-Identifier: GPL-3.0-or-later
// What to draw first when a view has no earlier frame to go by.
#pragma once

#include "mesolens/render/depth_pyramid.h"

#include <cstdint>
#include <vector>

namespace mesolens {

/// The cells to draw before the first visibility test of a view with no earlier frame (a first
/// frame, a jump): the nearest surface of what is in view, so that the test can find the rest
/// hidden. Walking `in_view` front to back (cells_in_view's order), a cell is chosen when its
/// footprint (CellAtoms::cell_footprint, boxes grown by `padding`) reaches a square of `block`
/// pixels of the `width` x `height` viewport that the footprints of the cells chosen before do
/// not cover whole; cells that must be drawn or have no footprint are always chosen. A footprint
/// can cover more than its atoms do: a cell left out then is found by the test, drawn after it.
/// Returns one flag per cell of `atoms` (1: draw first). `block` >= 1 pixels.
std::vector<std::uint8_t> first_occluders(const CellAtoms& atoms, const std::vector<float>& boxes,
                                          const std::vector<CellInView>& in_view, double padding,
                                          const ViewTransform& view, int width, int height,
                                          int block = 8);

} // namespace mesolens
