// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/text_fields.h"

#include <cctype>
#include <charconv>

namespace mesolens {
namespace detail {

namespace {
/// std::isspace in the "C" locale, without its per-character locale lookup.
bool is_blank(char c)
{
  return c == ' ' || (c >= '\t' && c <= '\r');
}

/// Calls visit(word) for each white-space separated word of the line, in order.
template<typename Visit>
void for_each_word(std::string_view line, Visit&& visit)
{
  for (std::size_t i = 0; i < line.size();)
  {
    while (i < line.size() && is_blank(line[i]))
    {
      ++i;
    }
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i]))
    {
      ++i;
    }
    if (i > start)
    {
      visit(line.substr(start, i - start));
    }
  }
}
} // namespace

std::vector<std::string_view> split_words(std::string_view line)
{
  std::vector<std::string_view> words;
  for_each_word(line, [&words](std::string_view word) { words.push_back(word); });
  return words;
}

std::size_t split_words(std::string_view line, std::string_view* words, std::size_t capacity)
{
  std::size_t count = 0;
  for_each_word(line, [&](std::string_view word) {
    if (count < capacity)
    {
      words[count] = word;
    }
    ++count;
  });
  return count;
}

bool parse_number(std::string_view word, double& value)
{
  const char* end = word.data() + word.size();
  // from_chars takes no leading '+', which some writers put.
  const char* begin = word.size() > 1 && word[0] == '+' ? word.data() + 1 : word.data();
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end;
}

bool parse_integer(std::string_view word, long long& value)
{
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

std::string quoted_field(std::string_view text)
{
  std::string shown(text.substr(0, 32));
  for (char& c : shown)
  {
    if (!std::isprint(static_cast<unsigned char>(c)))
    {
      c = '?';
    }
  }
  return shown;
}

} // namespace detail
} // namespace mesolens
