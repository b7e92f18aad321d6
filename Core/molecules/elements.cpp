// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/elements.h"

#include <gemmi/elem.hpp>

#include <array>
#include <cctype>
#include <string>

namespace mesolens {

namespace {
gemmi::El as_gemmi(int atomic_number)
{
  if (atomic_number < 0 || atomic_number > max_atomic_number)
  {
    return gemmi::El::X;
  }
  return static_cast<gemmi::El>(atomic_number);
}

std::string upper(const std::string& text)
{
  std::string out;
  for (const char c : text)
  {
    if (!std::isspace(static_cast<unsigned char>(c)))
    {
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return out;
}
} // namespace

const char* element_symbol(int atomic_number)
{
  return gemmi::element_name(as_gemmi(atomic_number));
}

int atomic_number_from_symbol(const std::string& symbol)
{
  const std::string key = upper(symbol);
  if (key.empty() || key.size() > 2)
  {
    return 0;
  }
  gemmi::El el = gemmi::find_element(key.c_str());
  if (el == gemmi::El::D)
  {
    el = gemmi::El::H;
  }
  return el == gemmi::El::END ? 0 : static_cast<int>(el);
}

float covalent_radius(int atomic_number)
{
  return gemmi::covalent_radius(as_gemmi(atomic_number));
}

float van_der_waals_radius(int atomic_number)
{
  return gemmi::vdw_radius(as_gemmi(atomic_number));
}

float atomic_mass(int atomic_number)
{
  if (atomic_number <= 0 || atomic_number > max_atomic_number)
  {
    return 1.0f;
  }
  return static_cast<float>(gemmi::molecular_weight(as_gemmi(atomic_number)));
}

int guess_atomic_number(const std::string& atom_name, const std::string& residue_name)
{
  const std::string name = upper(atom_name);
  const std::string residue = upper(residue_name);
  // Ion residues: the atom name repeats the residue name (NA/NA, CL/CL, ZN/ZN), or uses the
  // CHARMM four-letter ion names.
  struct IonName
  {
    const char* name;
    int atomic_number;
  };
  static const std::array<IonName, 8> charmm_ions = { { { "SOD", 11 },
                                                        { "POT", 19 },
                                                        { "CLA", 17 },
                                                        { "CAL", 20 },
                                                        { "CES", 55 },
                                                        { "LIT", 3 },
                                                        { "RUB", 37 },
                                                        { "ZN2", 30 } } };
  for (const IonName& ion : charmm_ions)
  {
    if (name == ion.name)
    {
      return ion.atomic_number;
    }
  }
  std::string letters;
  for (const char c : name)
  {
    if (std::isalpha(static_cast<unsigned char>(c)))
    {
      letters += c;
    }
  }
  if (letters.empty())
  {
    return 0;
  }
  if (letters.size() >= 2 && (name == residue || letters == residue))
  {
    const int two = atomic_number_from_symbol(letters.substr(0, 2));
    if (two != 0)
    {
      return two;
    }
  }
  return atomic_number_from_symbol(letters.substr(0, 1));
}

} // namespace mesolens
