// SPDX-License-Identifier: GPL-3.0-or-later
// The words and numbers of text mesh files, as the strict readers (OBJ, OFF, PLY) take them
// (private).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mesolens {
namespace detail {

/// A line of a text file, without its line end, and its 1-based number.
struct NumberedLine
{
  std::size_t number = 0;
  std::string_view text;
};

/// The white-space separated words of one line.
std::vector<std::string_view> split_words(std::string_view line);

/// The first `capacity` words of one line into `words`, without allocating; returns the
/// line's number of words, which may exceed `capacity`.
std::size_t split_words(std::string_view line, std::string_view* words, std::size_t capacity);

/// A whole word as a number (a leading '+' allowed; "nan" and "inf" parse: callers that need a
/// finite value check). False when the word is not one number.
bool parse_number(std::string_view word, double& value);

/// A whole word as an integer. False when it is not one, or out of range.
bool parse_integer(std::string_view word, long long& value);

/// At most 32 characters of `text`, those that do not print as '?': a message quotes the file.
std::string quoted_field(std::string_view text);

} // namespace detail
} // namespace mesolens
