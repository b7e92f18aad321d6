// SPDX-License-Identifier: GPL-3.0-or-later
// The mmCIF operator-expression parser of expand_operator_expression() (grammar in assembly.h).
#include "mesolens/common/errors.h"
#include "mesolens/protein/assembly.h"

#include <algorithm>
#include <cctype>

namespace mesolens {

namespace {

using Entry = AssemblyOperatorTable::value_type;
using Factor = std::vector<const Entry*>;

/// Parses one expression into its factors: lists of the operators they name, in order.
class ExpressionParser
{
public:
  ExpressionParser(const std::string& text, const AssemblyOperatorTable& operators,
                   std::size_t max_operators)
    : Text(text)
    , Operators(operators)
    , MaxOperators(max_operators)
  {
  }

  std::vector<Factor> factors()
  {
    std::vector<Factor> result;
    this->skip_blanks();
    if (this->at_end())
    {
      this->fail("is empty");
    }
    while (!this->at_end())
    {
      const bool parenthesized = this->Text[this->Position] == '(';
      this->Position += parenthesized ? 1 : 0;
      result.push_back(this->list(parenthesized));
      this->skip_blanks();
    }
    return result;
  }

private:
  Factor list(bool parenthesized)
  {
    Factor items;
    for (;;)
    {
      this->skip_blanks();
      const std::string first = this->id();
      this->skip_blanks();
      if (!this->at_end() && this->Text[this->Position] == '-')
      {
        ++this->Position;
        this->skip_blanks();
        this->add_range(first, this->id(), items);
      }
      else
      {
        this->add(first, items);
      }
      this->skip_blanks();
      if (this->at_end() || this->Text[this->Position] != ',')
      {
        break;
      }
      ++this->Position;
    }
    if (parenthesized)
    {
      if (this->at_end() || this->Text[this->Position] != ')')
      {
        this->fail("has no ')' to close its '(' (at character " + this->where() + ")");
      }
      ++this->Position;
    }
    else if (!this->at_end() && this->Text[this->Position] != '(')
    {
      this->fail("has '" + std::string(1, this->Text[this->Position]) + "' at character " +
                 this->where() + " where ',', '(' or the end was expected");
    }
    return items;
  }

  std::string id()
  {
    const std::size_t begin = this->Position;
    while (!this->at_end() && !is_special(this->Text[this->Position]))
    {
      ++this->Position;
    }
    if (this->Position == begin)
    {
      this->fail("has an empty operator id at character " + this->where());
    }
    return this->Text.substr(begin, this->Position - begin);
  }

  void add(const std::string& name, Factor& items)
  {
    const auto found = this->Operators.find(name);
    if (found == this->Operators.end())
    {
      this->fail("names operator '" + name + "', which is not defined");
    }
    if (items.size() >= this->MaxOperators)
    {
      this->fail("lists more than " + std::to_string(this->MaxOperators) + " operators");
    }
    items.push_back(&*found);
  }

  void add_range(const std::string& first_text, const std::string& last_text, Factor& items)
  {
    const long first = this->integer(first_text);
    const long last = this->integer(last_text);
    if (first > last)
    {
      this->fail("has the reversed range " + first_text + "-" + last_text);
    }
    // A range longer than the operator list must name an undefined id: add() finds the first.
    const long longest = long(std::min<std::size_t>(this->Operators.size(), 1000000000)) + 1;
    const long end = last - first < longest ? last + 1 : first + longest;
    for (long n = first; n < end; ++n)
    {
      this->add(std::to_string(n), items);
    }
  }

  long integer(const std::string& text)
  {
    if (text.size() > 9 ||
        !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    {
      this->fail("has the range end '" + text + "', which is not an integer of up to 9 digits");
    }
    return std::stol(text);
  }

  static bool is_special(char c)
  {
    return c == '(' || c == ')' || c == ',' || c == '-' ||
      std::isspace(static_cast<unsigned char>(c));
  }

  void skip_blanks()
  {
    while (!this->at_end() && std::isspace(static_cast<unsigned char>(this->Text[this->Position])))
    {
      ++this->Position;
    }
  }

  bool at_end() const
  {
    return this->Position >= this->Text.size();
  }

  std::string where() const
  {
    return std::to_string(this->Position + 1);
  }

  [[noreturn]] void fail(const std::string& problem) const
  {
    const std::size_t shown = 60;
    const std::string text =
      this->Text.size() > shown ? this->Text.substr(0, shown) + "..." : this->Text;
    throw InvalidInput("the operator expression '" + text + "' " + problem);
  }

  const std::string& Text;
  const AssemblyOperatorTable& Operators;
  const std::size_t MaxOperators;
  std::size_t Position = 0;
};

} // namespace

std::vector<AssemblyOperator> expand_operator_expression(const std::string& expression,
                                                         const AssemblyOperatorTable& operators,
                                                         std::size_t max_operators)
{
  const std::vector<Factor> factors =
    ExpressionParser(expression, operators, max_operators).factors();
  std::size_t count = 1;
  for (const Factor& factor : factors)
  {
    if (count > max_operators / factor.size())
    {
      throw InvalidInput("the operator expression '" + expression.substr(0, 60) +
                         "' gives more than " + std::to_string(max_operators) + " operators");
    }
    count *= factor.size();
  }
  // The first factor varies slowest: the product is built left to right, each new factor
  // applied first (rightmost).
  std::vector<AssemblyOperator> product;
  for (const Entry* entry : factors.front())
  {
    product.push_back({ entry->first, entry->second });
  }
  for (std::size_t f = 1; f < factors.size(); ++f)
  {
    std::vector<AssemblyOperator> next;
    next.reserve(product.size() * factors[f].size());
    for (const AssemblyOperator& left : product)
    {
      for (const Entry* right : factors[f])
      {
        next.push_back({ left.name + "x" + right->first, compose(left.matrix, right->second) });
      }
    }
    product = std::move(next);
  }
  return product;
}

} // namespace mesolens
