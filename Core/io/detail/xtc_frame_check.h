// SPDX-License-Identifier: GPL-3.0-or-later
// Validation of one compressed XTC frame before GROMACS decodes it (private).
#pragma once

#include <cstdint>
#include <string>

namespace mesolens {
namespace detail {

/// Walks the compressed coordinate bit stream of the XTC frame at `offset` the way GROMACS'
/// decoder (xdr3dfcoord) will, without decoding values, and throws FileError when the decoder
/// would divide by zero, index its tables out of range, write past the atom array or read past
/// the frame's bytes. GROMACS performs none of these checks, so a corrupt frame would otherwise
/// crash the process.
void check_xtc_frame(const std::string& path, std::int64_t offset);

} // namespace detail
} // namespace mesolens
