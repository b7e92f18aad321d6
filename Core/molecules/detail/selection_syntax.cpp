// SPDX-License-Identifier: GPL-3.0-or-later
#include "molecules/detail/selection_syntax.h"

#include "mesolens/molecules/atom_selection.h"
#include "mesolens/molecules/elements.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>

namespace mesolens {
namespace detail {

namespace {

struct Token
{
  enum class Kind
  {
    Word,
    Quoted,
    Open,
    Close,
    Operator,
    End,
  };
  Kind kind = Kind::End;
  std::string text;
  std::size_t position = 0;
};

bool is_operator_char(char c)
{
  return c == '<' || c == '>' || c == '=' || c == '!';
}

bool ends_word(char c)
{
  return std::isspace(static_cast<unsigned char>(c)) || c == '(' || c == ')' || c == '"' ||
    is_operator_char(c);
}

/// Splits the expression into words, quoted strings, parentheses and comparison operators.
class Tokenizer
{
public:
  explicit Tokenizer(const std::string& text)
    : Text(text)
  {
  }

  std::vector<Token> tokens()
  {
    std::vector<Token> tokens;
    std::size_t i = 0;
    while (true)
    {
      while (i < this->Text.size() && std::isspace(static_cast<unsigned char>(this->Text[i])))
      {
        ++i;
      }
      if (i == this->Text.size())
      {
        tokens.push_back({ Token::Kind::End, "", i });
        return tokens;
      }
      tokens.push_back(this->next(i));
    }
  }

private:
  Token next(std::size_t& i) const
  {
    const std::size_t start = i;
    const char c = this->Text[i];
    if (c == '(' || c == ')')
    {
      ++i;
      return { c == '(' ? Token::Kind::Open : Token::Kind::Close, std::string(1, c), start };
    }
    if (c == '"')
    {
      const std::size_t close = this->Text.find('"', i + 1);
      if (close == std::string::npos)
      {
        throw SelectionError(
          selection_error_message(this->Text, "unterminated quoted string", start), start);
      }
      i = close + 1;
      return { Token::Kind::Quoted, this->Text.substr(start + 1, close - start - 1), start };
    }
    if (is_operator_char(c))
    {
      while (i < this->Text.size() && is_operator_char(this->Text[i]))
      {
        ++i;
      }
      return { Token::Kind::Operator, this->Text.substr(start, i - start), start };
    }
    while (i < this->Text.size() && !ends_word(this->Text[i]))
    {
      ++i;
    }
    return { Token::Kind::Word, this->Text.substr(start, i - start), start };
  }

  const std::string& Text;
};

const std::map<std::string, AtomClass>& class_keywords()
{
  static const std::map<std::string, AtomClass> keywords = {
    { "all", AtomClass::All },           { "none", AtomClass::None },
    { "protein", AtomClass::Protein },   { "nucleic", AtomClass::Nucleic },
    { "water", AtomClass::Water },       { "lipid", AtomClass::Lipid },
    { "backbone", AtomClass::Backbone }, { "hydrogen", AtomClass::Hydrogen },
    { "hetero", AtomClass::Hetero },
  };
  return keywords;
}

const std::map<std::string, TextField>& text_keywords()
{
  static const std::map<std::string, TextField> keywords = {
    { "name", TextField::Name },     { "resname", TextField::ResidueName },
    { "chain", TextField::Chain },   { "chainid", TextField::Chain },
    { "altloc", TextField::AltLoc },
  };
  return keywords;
}

/// Integer fields: range lists after the keyword, or comparisons.
const std::map<std::string, NumberField>& integer_keywords()
{
  static const std::map<std::string, NumberField> keywords = {
    { "resid", NumberField::ResidueNumber },  { "resnum", NumberField::ResidueNumber },
    { "index", NumberField::Index },          { "bynum", NumberField::PositionNumber },
    { "serial", NumberField::Serial },        { "id", NumberField::Serial },
    { "residue", NumberField::ResidueIndex }, { "resindex", NumberField::ResidueIndex },
    { "molecule", NumberField::Molecule },
  };
  return keywords;
}

/// Fields that are only compared.
const std::map<std::string, NumberField>& value_fields()
{
  static const std::map<std::string, NumberField> fields = {
    { "x", NumberField::X },
    { "y", NumberField::Y },
    { "z", NumberField::Z },
    { "occupancy", NumberField::Occupancy },
    { "beta", NumberField::BFactor },
    { "bfactor", NumberField::BFactor },
    { "tempfactor", NumberField::BFactor },
    { "charge", NumberField::FormalCharge },
    { "mass", NumberField::Mass },
  };
  return fields;
}

const std::map<std::string, Comparison>& comparisons()
{
  static const std::map<std::string, Comparison> operators = {
    { "<", Comparison::Less },      { "<=", Comparison::LessEqual },
    { ">", Comparison::Greater },   { ">=", Comparison::GreaterEqual },
    { "==", Comparison::Equal },    { "=", Comparison::Equal },
    { "!=", Comparison::NotEqual },
  };
  return operators;
}

/// Words that end a value list: operators of the grammar and every keyword.
bool is_reserved(const std::string& word)
{
  static const char* const grammar[] = { "and",    "or",   "not",   "within", "exwithin",
                                         "around", "same", "byres", "prop",   "element",
                                         "to",     "of",   "as" };
  for (const char* reserved : grammar)
  {
    if (word == reserved)
    {
      return true;
    }
  }
  return class_keywords().count(word) || text_keywords().count(word) ||
    integer_keywords().count(word);
}

std::optional<double> parse_number(const std::string& text)
{
  if (text.empty())
  {
    return std::nullopt;
  }
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
  {
    return std::nullopt;
  }
  return value;
}

// Numbers and ranges are short; longer words are refused before any regex sees them.
constexpr std::size_t longest_number = 40;

std::optional<long long> parse_integer(const std::string& text)
{
  static const std::regex integer("[-+]?[0-9]{1,18}");
  if (text.size() > longest_number || !std::regex_match(text, integer))
  {
    return std::nullopt;
  }
  return std::strtoll(text.c_str(), nullptr, 10);
}

/// Recursive descent over the tokens; each method consumes what it parses.
class Parser
{
public:
  explicit Parser(const std::string& expression)
    : Expression(expression)
    , Tokens(Tokenizer(expression).tokens())
  {
  }

  std::unique_ptr<SelectionNode> parse()
  {
    if (this->peek().kind == Token::Kind::End)
    {
      this->fail("empty selection", this->peek());
    }
    auto root = this->expression();
    const Token& rest = this->peek();
    if (rest.kind == Token::Kind::Close)
    {
      this->fail("')' without a matching '('", rest);
    }
    if (rest.kind != Token::Kind::End)
    {
      this->fail("expected 'and', 'or' or the end, found '" + rest.text + "'", rest);
    }
    return root;
  }

private:
  [[noreturn]] void fail(const std::string& problem, const Token& token) const
  {
    throw SelectionError(selection_error_message(this->Expression, problem, token.position),
                         token.position);
  }

  const Token& peek(std::size_t ahead = 0) const
  {
    return this->Tokens[std::min(this->Next + ahead, this->Tokens.size() - 1)];
  }

  const Token& take()
  {
    return this->Tokens[std::min(this->Next++, this->Tokens.size() - 1)];
  }

  bool at_word(const char* word, std::size_t ahead = 0) const
  {
    return this->peek(ahead).kind == Token::Kind::Word && this->peek(ahead).text == word;
  }

  static std::unique_ptr<SelectionNode> node(SelectionNode::Kind kind, std::size_t position)
  {
    auto result = std::make_unique<SelectionNode>();
    result->kind = kind;
    result->position = position;
    return result;
  }

  /// Operands joined by `word` ("and"/"or") as one node of all of them (a flat list, so a
  /// long chain does not make a deep tree).
  template<typename Operand>
  std::unique_ptr<SelectionNode> chain(SelectionNode::Kind kind, const char* word, Operand operand)
  {
    auto first = (this->*operand)();
    if (!this->at_word(word))
    {
      return first;
    }
    auto result = node(kind, first->position);
    result->operands.push_back(std::move(first));
    while (this->at_word(word))
    {
      this->take();
      result->operands.push_back((this->*operand)());
    }
    return result;
  }

  std::unique_ptr<SelectionNode> expression()
  {
    return this->chain(SelectionNode::Kind::Or, "or", &Parser::term);
  }

  std::unique_ptr<SelectionNode> term()
  {
    return this->chain(SelectionNode::Kind::And, "and", &Parser::factor);
  }

  std::unique_ptr<SelectionNode> factor()
  {
    const Token& token = this->peek();
    // Each level is a C++ call: a hostile expression of a million '(' must not exhaust the stack.
    constexpr std::size_t deepest_nesting = 256;
    if (++this->Depth > deepest_nesting)
    {
      this->fail("more than " + std::to_string(deepest_nesting) + " nested operators", token);
    }
    auto result = this->nested_factor(token);
    --this->Depth;
    return result;
  }

  std::unique_ptr<SelectionNode> nested_factor(const Token& token)
  {
    if (token.kind == Token::Kind::Open)
    {
      this->take();
      auto inner = this->expression();
      if (this->peek().kind != Token::Kind::Close)
      {
        this->fail(this->peek().kind == Token::Kind::End
                     ? std::string("missing ')'")
                     : "expected 'and', 'or' or ')', found '" + this->peek().text + "'",
                   this->peek());
      }
      this->take();
      return inner;
    }
    if (token.kind == Token::Kind::End)
    {
      this->fail("the selection ends where a keyword or '(' is expected", token);
    }
    if (token.kind != Token::Kind::Word)
    {
      this->fail("expected a keyword or '(', found '" + token.text + "'", token);
    }
    if (token.text == "not")
    {
      auto result = node(SelectionNode::Kind::Not, this->take().position);
      result->operands.push_back(this->factor());
      return result;
    }
    return this->clause();
  }

  std::unique_ptr<SelectionNode> clause()
  {
    const Token& token = this->peek();
    const std::string& word = token.text;
    if (word == "within" || word == "exwithin" || word == "around")
    {
      return this->within();
    }
    if (word == "same" || word == "byres")
    {
      return this->same();
    }
    if (word == "prop" || this->peek(1).kind == Token::Kind::Operator)
    {
      return this->comparison();
    }
    if (word == "element")
    {
      return this->elements();
    }
    const auto atom_class = class_keywords().find(word);
    if (atom_class != class_keywords().end())
    {
      auto result = node(SelectionNode::Kind::Class, this->take().position);
      result->atom_class = atom_class->second;
      return result;
    }
    const auto text = text_keywords().find(word);
    if (text != text_keywords().end())
    {
      auto result = node(SelectionNode::Kind::Text, this->take().position);
      result->text_field = text->second;
      result->patterns = this->values(token);
      return result;
    }
    const auto integer = integer_keywords().find(word);
    if (integer != integer_keywords().end())
    {
      return this->ranges(integer->second);
    }
    this->fail("unknown keyword '" + word + "'", token);
  }

  /// The words after a keyword, up to the next reserved word, parenthesis or operator.
  std::vector<std::string> values(const Token& keyword)
  {
    std::vector<std::string> result;
    while (this->peek().kind == Token::Kind::Quoted ||
           (this->peek().kind == Token::Kind::Word && !is_reserved(this->peek().text)))
    {
      result.push_back(this->take().text);
    }
    if (result.empty())
    {
      this->fail("'" + keyword.text + "' needs at least one value", this->peek());
    }
    return result;
  }

  std::unique_ptr<SelectionNode> elements()
  {
    const Token& keyword = this->peek();
    auto result = node(SelectionNode::Kind::Element, this->take().position);
    const std::size_t first = this->Next;
    const std::vector<std::string> symbols = this->values(keyword);
    for (std::size_t k = 0; k < symbols.size(); ++k)
    {
      const int number = atomic_number_from_symbol(symbols[k]);
      if (number == 0)
      {
        this->fail("'" + symbols[k] + "' is not an element symbol", this->Tokens[first + k]);
      }
      result->atomic_numbers.push_back(number);
    }
    return result;
  }

  std::unique_ptr<SelectionNode> ranges(NumberField field)
  {
    const Token& keyword = this->peek();
    if (this->peek(1).kind == Token::Kind::Operator)
    {
      return this->comparison();
    }
    auto result = node(SelectionNode::Kind::Ranges, this->take().position);
    result->number_field = field;
    while (this->peek().kind == Token::Kind::Word && !is_reserved(this->peek().text))
    {
      result->ranges.push_back(this->range(field == NumberField::ResidueNumber));
    }
    if (result->ranges.empty())
    {
      this->fail("'" + keyword.text + "' needs at least one number or range", this->peek());
    }
    return result;
  }

  /// `5`, `-3`, `52A`, `5-10`, `5:10`, `-10--5`, or `5 to 10`.
  IntegerRange range(bool insertion_codes)
  {
    const Token& token = this->take();
    static const std::regex pattern("([-+]?[0-9]{1,18})([A-Za-z]?)(?:[-:]([-+]?[0-9]{1,18}))?");
    std::smatch match;
    if (token.text.size() > longest_number || !std::regex_match(token.text, match, pattern) ||
        (match[2].length() > 0 && (!insertion_codes || match[3].matched)))
    {
      this->fail("'" + token.text + "' is not a number or a range", token);
    }
    IntegerRange result;
    result.low = std::strtoll(match[1].str().c_str(), nullptr, 10);
    result.high = result.low;
    result.insertion_code = match[2].length() > 0 ? match[2].str()[0] : 0;
    if (match[3].matched)
    {
      result.high = std::strtoll(match[3].str().c_str(), nullptr, 10);
    }
    else if (this->at_word("to") && result.insertion_code == 0)
    {
      this->take();
      const Token& upper = this->take();
      const auto high = parse_integer(upper.text);
      if (upper.kind != Token::Kind::Word || !high)
      {
        this->fail("expected a number after 'to'", upper);
      }
      result.high = *high;
    }
    if (result.high < result.low)
    {
      this->fail("the range '" + token.text + "' runs backwards", token);
    }
    return result;
  }

  std::unique_ptr<SelectionNode> comparison()
  {
    if (this->at_word("prop"))
    {
      this->take();
    }
    const Token& field = this->take();
    auto result = node(SelectionNode::Kind::Compare, field.position);
    if (field.kind != Token::Kind::Word || parse_number(field.text))
    {
      this->fail("expected a field name to compare", field);
    }
    const auto builtin = value_fields().find(field.text);
    const auto integer = integer_keywords().find(field.text);
    if (builtin != value_fields().end())
    {
      result->number_field = builtin->second;
    }
    else if (integer != integer_keywords().end())
    {
      result->number_field = integer->second;
    }
    else
    {
      result->number_field = NumberField::Array;
      result->array_name = field.text;
    }
    const Token& op = this->take();
    const auto comparison = comparisons().find(op.text);
    if (op.kind != Token::Kind::Operator || comparison == comparisons().end())
    {
      this->fail("expected <, <=, >, >=, == or != after '" + field.text + "'", op);
    }
    result->comparison = comparison->second;
    const Token& number = this->take();
    const auto value = parse_number(number.text);
    if (number.kind != Token::Kind::Word || !value)
    {
      this->fail("expected a number after '" + op.text + "'", number);
    }
    result->value = *value;
    return result;
  }

  std::unique_ptr<SelectionNode> within()
  {
    const Token& keyword = this->take();
    auto result = node(SelectionNode::Kind::Within, keyword.position);
    result->exclusive = keyword.text != "within";
    const Token& distance = this->take();
    const auto value = parse_number(distance.text);
    if (distance.kind != Token::Kind::Word || !value || *value < 0.0)
    {
      this->fail("expected a distance in Å (a number >= 0) after '" + keyword.text + "'", distance);
    }
    result->distance = *value;
    if (keyword.text != "around")
    {
      if (!this->at_word("of"))
      {
        this->fail("expected 'of' after '" + keyword.text + " " + distance.text + "'",
                   this->peek());
      }
      this->take();
    }
    result->operands.push_back(this->factor());
    return result;
  }

  std::unique_ptr<SelectionNode> same()
  {
    const Token& keyword = this->take();
    auto result = node(SelectionNode::Kind::Same, keyword.position);
    if (keyword.text == "same")
    {
      static const std::map<std::string, Grouping> groupings = {
        { "residue", Grouping::Residue },
        { "chain", Grouping::Chain },
        { "molecule", Grouping::Molecule },
      };
      const Token& grouping = this->take();
      const auto found = groupings.find(grouping.text);
      if (grouping.kind != Token::Kind::Word || found == groupings.end())
      {
        this->fail("expected 'residue', 'chain' or 'molecule' after 'same'", grouping);
      }
      result->grouping = found->second;
      if (!this->at_word("as"))
      {
        this->fail("expected 'as' after 'same " + grouping.text + "'", this->peek());
      }
      this->take();
    }
    result->operands.push_back(this->factor());
    return result;
  }

  const std::string& Expression;
  std::vector<Token> Tokens;
  std::size_t Next = 0;
  std::size_t Depth = 0;
};

} // namespace

std::string selection_error_message(const std::string& expression, const std::string& problem,
                                    std::size_t position)
{
  // One line, whatever the expression holds.
  std::string shown = expression;
  for (char& c : shown)
  {
    if (std::iscntrl(static_cast<unsigned char>(c)))
    {
      c = ' ';
    }
  }
  return "selection \"" + shown + "\": " + problem + " at character " +
    std::to_string(position + 1);
}

std::unique_ptr<SelectionNode> parse_selection(const std::string& expression)
{
  return Parser(expression).parse();
}

} // namespace detail
} // namespace mesolens
