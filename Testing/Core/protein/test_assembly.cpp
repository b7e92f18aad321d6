// SPDX-License-Identifier: GPL-3.0-or-later
// Biological assemblies: the operator-expression parser on analytic cases, the assemblies of
// real files against gemmi's make_assembly (gemmi 0.5.7, read here directly), and malformed
// assembly records. gemmi 0.5.7 expands only the first list of an mmCIF product (60 of
// 1m4x.cif's 1680 operators): there the PDB file's BIOMT list is the oracle.
#include "mesolens/common/errors.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/protein/assembly.h"
#include "mesolens_test_data.h"

#include <gemmi/assembly.hpp>
#include <gemmi/gz.hpp>
#include <gemmi/mmread.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

namespace {

using mesolens::AssemblyMatrix;
using mesolens::AssemblyOperatorTable;

AssemblyMatrix rotation_z_90(double tx = 0, double ty = 0, double tz = 0)
{
  return { 0, -1, 0, tx, 1, 0, 0, ty, 0, 0, 1, tz };
}

AssemblyMatrix rotation_x_90()
{
  return { 1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0 };
}

AssemblyMatrix translation(double x, double y, double z)
{
  return { 1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z };
}

std::vector<std::string> names(const std::vector<mesolens::AssemblyOperator>& operators)
{
  std::vector<std::string> result;
  for (const auto& op : operators)
  {
    result.push_back(op.name);
  }
  return result;
}

void expect_near(const AssemblyMatrix& a, const AssemblyMatrix& b, double tolerance = 1e-12)
{
  for (std::size_t k = 0; k < 12; ++k)
  {
    EXPECT_NEAR(a[k], b[k], tolerance) << "entry " << k;
  }
}

mesolens::StructureFile read_all_atoms(const std::string& path)
{
  mesolens::StructureReadParams params;
  params.alt_locs = mesolens::AltLocPolicy::KeepAll; // gemmi keeps every conformer
  return mesolens::read_structure(path, params);
}

bool has_warning(const mesolens::StructureFile& file, const std::string& text)
{
  for (const std::string& warning : file.warnings)
  {
    if (warning.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

/// The copies' atoms from the instances, in expand_assembly()'s order, must be the expansion.
void expect_instances_match_expansion(const mesolens::AtomTable& unit,
                                      const mesolens::Assembly& assembly,
                                      const mesolens::AssemblyExpansion& expanded)
{
  const mesolens::AssemblyInstances instances = mesolens::assembly_instances(unit, assembly);
  ASSERT_EQ(instances.instances.size(), assembly.copy_count());
  std::size_t row = 0;
  for (std::size_t c = 0; c < instances.instances.size(); ++c)
  {
    const auto& instance = instances.instances[c];
    const auto& set = instances.atom_sets.at(instance.atom_set);
    for (const std::uint32_t i : set.atoms)
    {
      ASSERT_LT(row, expanded.atoms.size());
      EXPECT_EQ(expanded.copy_of_atom[row], int(c));
      const auto p = mesolens::transform_point(
        instance.matrix,
        { unit.positions[3 * i], unit.positions[3 * i + 1], unit.positions[3 * i + 2] });
      double distance = 0;
      for (std::size_t d = 0; d < 3; ++d)
      {
        distance = std::max(distance, std::abs(p[d] - expanded.atoms.positions[3 * row + d]));
        distance = std::max(distance, std::abs(p[d] - instance.center[d]) - instance.radius);
      }
      EXPECT_LT(distance, 1e-3) << "copy " << c << " atom " << i;
      ++row;
    }
  }
  EXPECT_EQ(row, expanded.atoms.size());
}

// --- the operator expression --------------------------------------------------------------

AssemblyOperatorTable numbered_operators(int count)
{
  AssemblyOperatorTable table;
  for (int n = 1; n <= count; ++n)
  {
    table[std::to_string(n)] = translation(n, 0, 0);
  }
  return table;
}

/// Each (assembly, reason) pair is named by one of the file's warnings, and there is one
/// warning per pair.
template<std::size_t N>
void expect_warnings(const mesolens::StructureFile& file,
                     const std::pair<const char*, const char*> (&expected)[N])
{
  for (const auto& [assembly, reason] : expected)
  {
    bool found = false;
    for (const std::string& warning : file.warnings)
    {
      found = found ||
        (warning.find(assembly) != std::string::npos && warning.find(reason) != std::string::npos);
    }
    EXPECT_TRUE(found) << assembly << " with " << reason;
  }
  EXPECT_EQ(file.warnings.size(), N);
}

TEST(OperatorExpression, ListsRangesAndIds)
{
  AssemblyOperatorTable table = numbered_operators(60);
  table["P"] = rotation_x_90();
  table["X0"] = rotation_z_90();
  using List = std::vector<std::string>;
  EXPECT_EQ(names(mesolens::expand_operator_expression("1", table)), List{ "1" });
  EXPECT_EQ(names(mesolens::expand_operator_expression("1,2,5", table)), (List{ "1", "2", "5" }));
  EXPECT_EQ(mesolens::expand_operator_expression("(1-60)", table).size(), 60u);
  EXPECT_EQ(names(mesolens::expand_operator_expression("(1,2,5-8)", table)),
            (List{ "1", "2", "5", "6", "7", "8" }));
  EXPECT_EQ(names(mesolens::expand_operator_expression(" ( 1 , 3 - 4 ) ", table)),
            (List{ "1", "3", "4" }));
  EXPECT_EQ(names(mesolens::expand_operator_expression("P", table)), List{ "P" });
  EXPECT_EQ(names(mesolens::expand_operator_expression("(X0)", table)), List{ "X0" });
  EXPECT_EQ(names(mesolens::expand_operator_expression("7-7", table)), List{ "7" });
  const auto ops = mesolens::expand_operator_expression("(5-8)", table);
  expect_near(ops[2].matrix, translation(7, 0, 0));
}

TEST(OperatorExpression, ProductsComposeRightmostFirst)
{
  AssemblyOperatorTable table;
  table["1"] = rotation_z_90();
  table["2"] = translation(1, 0, 0);
  table["3"] = rotation_x_90();
  // (1)(2): translate, then rotate: the origin goes to Rz(1, 0, 0) = (0, 1, 0).
  const auto one_two = mesolens::expand_operator_expression("(1)(2)", table);
  ASSERT_EQ(one_two.size(), 1u);
  EXPECT_EQ(one_two[0].name, "1x2");
  const auto p = mesolens::transform_point(one_two[0].matrix, { 0, 0, 0 });
  EXPECT_NEAR(p[0], 0, 1e-12);
  EXPECT_NEAR(p[1], 1, 1e-12);
  const auto two_one = mesolens::expand_operator_expression("(2)(1)", table);
  const auto q = mesolens::transform_point(two_one[0].matrix, { 0, 0, 0 });
  EXPECT_NEAR(q[0], 1, 1e-12);
  EXPECT_NEAR(q[1], 0, 1e-12);
  // Two non-commuting rotations: Rz·Rx maps y to z... composed as left·right.
  const auto zx = mesolens::expand_operator_expression("(1)(3)", table)[0];
  expect_near(zx.matrix, mesolens::compose(rotation_z_90(), rotation_x_90()));
  const auto y = mesolens::transform_point(zx.matrix, { 0, 1, 0 }); // Rx: y -> z; Rz: z -> z
  EXPECT_NEAR(y[2], 1, 1e-12);
  const auto xz = mesolens::expand_operator_expression("(3)(1)", table)[0];
  const auto y2 = mesolens::transform_point(xz.matrix, { 0, 1, 0 }); // Rz: y -> -x; Rx: -x
  EXPECT_NEAR(y2[0], -1, 1e-12);
  // The first factor varies slowest; three factors multiply their lengths.
  const auto product = mesolens::expand_operator_expression("(1,2)(2,3)", table);
  EXPECT_EQ(names(product), (std::vector<std::string>{ "1x2", "1x3", "2x2", "2x3" }));
  expect_near(product[3].matrix, mesolens::compose(translation(1, 0, 0), rotation_x_90()));
  EXPECT_EQ(mesolens::expand_operator_expression("(1,2)(1-3)(2,3)", table).size(), 12u);
  EXPECT_EQ(names(mesolens::expand_operator_expression("P(1,2)",
                                                       [] {
                                                         AssemblyOperatorTable t =
                                                           numbered_operators(2);
                                                         t["P"] = rotation_x_90();
                                                         return t;
                                                       }())),
            (std::vector<std::string>{ "Px1", "Px2" }));
}

TEST(OperatorExpression, BadExpressionsThrowNamingTheProblem)
{
  const AssemblyOperatorTable table = numbered_operators(60);
  const std::pair<const char*, const char*> bad[] = {
    { "", "empty" },
    { "   ", "empty" },
    { "()", "empty operator id" },
    { "(1", "no ')'" },
    { "1)", "')'" },
    { "(1,,2)", "empty operator id" },
    { "(5-1)", "reversed range 5-1" },
    { "(1-a)", "'a'" },
    { "(1-)", "empty operator id" },
    { "(-1)", "empty operator id" },
    { "(61)", "'61'" },
    { "(1-61)", "'61'" },
    { "(1-999999999)", "'61'" },
    { "(1-9999999999)", "up to 9 digits" },
    { "1 2", "'2'" },
    { "Q", "'Q'" },
    { "(1-60)(1-60)(1-60)(1-60)", "more than 1000000" },
  };
  for (const auto& [expression, message] : bad)
  {
    try
    {
      mesolens::expand_operator_expression(expression, table);
      ADD_FAILURE() << "no error for '" << expression << "'";
    }
    catch (const mesolens::InvalidInput& e)
    {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
        << "'" << expression << "': " << e.what();
    }
  }
  // A list of the allowed length passes; one more operator does not.
  EXPECT_EQ(mesolens::expand_operator_expression("(1-60)(1-60)", table, 3600).size(), 3600u);
  EXPECT_THROW(mesolens::expand_operator_expression("(1-60)(1-60)", table, 3599),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::expand_operator_expression("(1-60)", table, 59), mesolens::InvalidInput);
}

TEST(Assembly, MatricesAndNames)
{
  const AssemblyMatrix m = mesolens::compose(translation(1, 2, 3), rotation_z_90());
  const auto p = mesolens::transform_point(m, { 1, 0, 0 });
  EXPECT_NEAR(p[0], 1, 1e-12);
  EXPECT_NEAR(p[1], 3, 1e-12);
  EXPECT_NEAR(p[2], 3, 1e-12);
  expect_near(mesolens::compose(mesolens::identity_assembly_matrix(), m), m);
  EXPECT_EQ(mesolens::assembly_chain_name("A", 0), "A");
  EXPECT_EQ(mesolens::assembly_chain_name("A", 1), "A-2");
  EXPECT_EQ(mesolens::assembly_chain_name("AB", 59), "AB-60");
  mesolens::Assembly assembly;
  assembly.name = "1";
  assembly.generators.resize(2);
  assembly.generators[0].operators.resize(3);
  assembly.generators[1].operators.resize(2);
  EXPECT_EQ(assembly.copy_count(), 5u);
  const std::vector<mesolens::Assembly> list{ assembly };
  EXPECT_EQ(mesolens::find_assembly(list, "1"), &list[0]);
  EXPECT_EQ(mesolens::find_assembly(list, "2"), nullptr);
  EXPECT_EQ(mesolens::find_assembly(list, ""), nullptr);
}

TEST(Assembly, OperatorsBeyondFloatRangeAreRefused)
{
  mesolens::AtomTable table;
  table.append_atom("CA", 1000, 0, 0);
  table.chain_ids.back() = "A";
  mesolens::Assembly assembly;
  assembly.name = "far";
  assembly.generators.resize(1);
  assembly.generators[0].chains = { "A" };
  assembly.generators[0].operators = { { "1", mesolens::identity_assembly_matrix() },
                                       { "2", translation(1e39, 0, 0) } };
  EXPECT_THROW(mesolens::expand_assembly(table, assembly), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::assembly_instances(table, assembly), mesolens::InvalidInput);
  assembly.generators[0].operators[1].matrix = { 1e36, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
  EXPECT_THROW(mesolens::expand_assembly(table, assembly), mesolens::InvalidInput);
  assembly.generators[0].operators[1].matrix = translation(1e30, 0, 0);
  const mesolens::AssemblyExpansion expanded = mesolens::expand_assembly(table, assembly);
  EXPECT_FLOAT_EQ(expanded.atoms.positions[3], 1e30f);
  // A generator naming label_asym_ids of a table without them.
  table.label_asym_ids.clear();
  assembly.generators[0].chain_ids = mesolens::AssemblyChainIds::Label;
  EXPECT_THROW(mesolens::assembly_atom_count(table, assembly), mesolens::InvalidInput);
}

// --- mmCIF: label_asym_ids, generators, expansion ----------------------------------------

std::string oper_row(const std::string& id, const AssemblyMatrix& m)
{
  std::string row = id + " 'point symmetry operation'";
  for (const double v : m)
  {
    char value[32];
    std::snprintf(value, sizeof value, " %.6f", v);
    row += value;
  }
  return row + "\n";
}

/// A small mmCIF file: chain A's glycine (label_asym_id A) and two waters (C), chain B's
/// glycine (B); `assemblies` rows are "id details" (the columns gemmi needs to read them are
/// added, so that gemmi would parse the generators too), `generators` and `operators` whole
/// rows.
std::string mmcif_file(const std::string& assemblies, const std::string& generators,
                       const std::string& operators)
{
  std::string text = "data_TEST\n#\nloop_\n";
  for (const char* tag : { "group_PDB",      "id",
                           "type_symbol",    "label_atom_id",
                           "label_alt_id",   "label_comp_id",
                           "label_asym_id",  "label_entity_id",
                           "label_seq_id",   "pdbx_PDB_ins_code",
                           "Cartn_x",        "Cartn_y",
                           "Cartn_z",        "occupancy",
                           "B_iso_or_equiv", "auth_seq_id",
                           "auth_comp_id",   "auth_asym_id",
                           "auth_atom_id",   "pdbx_PDB_model_num" })
  {
    text += std::string("_atom_site.") + tag + "\n";
  }
  text += "ATOM   1 N N  . GLY A 1 1 ? 1.000 0.000 0.000 1.00 10.0 1 GLY A N  1\n"
          "ATOM   2 C CA . GLY A 1 1 ? 2.450 0.000 0.000 1.00 10.0 1 GLY A CA 1\n"
          "ATOM   3 C C  . GLY A 1 1 ? 3.000 1.400 0.000 1.00 10.0 1 GLY A C  1\n"
          "ATOM   4 O O  . GLY A 1 1 ? 2.300 2.400 0.000 1.00 10.0 1 GLY A O  1\n"
          "ATOM   5 N N  . GLY B 1 1 ? 11.000 0.000 0.000 1.00 10.0 1 GLY B N  1\n"
          "ATOM   6 C CA . GLY B 1 1 ? 12.450 0.000 0.000 1.00 10.0 1 GLY B CA 1\n"
          "HETATM 7 O O  . HOH C 2 . ? 5.000 5.000 5.000 1.00 10.0 101 HOH A O 1\n"
          "HETATM 8 O O  . HOH C 2 . ? 8.000 5.000 5.000 1.00 10.0 102 HOH A O 1\n#\n";
  text += "loop_\n_pdbx_struct_assembly.id\n_pdbx_struct_assembly.details\n"
          "_pdbx_struct_assembly.method_details\n_pdbx_struct_assembly.oligomeric_details\n"
          "_pdbx_struct_assembly.oligomeric_count\n";
  for (std::size_t start = 0, end; (end = assemblies.find('\n', start)) != std::string::npos;
       start = end + 1)
  {
    text += assemblies.substr(start, end - start) + " ? ? ?\n";
  }
  text += "#\nloop_\n_pdbx_struct_assembly_gen.assembly_id\n"
          "_pdbx_struct_assembly_gen.oper_expression\n_pdbx_struct_assembly_gen.asym_id_list\n" +
    generators;
  text += "#\nloop_\n_pdbx_struct_oper_list.id\n_pdbx_struct_oper_list.type\n";
  for (int i = 1; i <= 3; ++i)
  {
    for (int j = 1; j <= 3; ++j)
    {
      text +=
        "_pdbx_struct_oper_list.matrix[" + std::to_string(i) + "][" + std::to_string(j) + "]\n";
    }
    text += "_pdbx_struct_oper_list.vector[" + std::to_string(i) + "]\n";
  }
  return text + operators + "#\n";
}

TEST(Assembly, MmcifGeneratorsSelectLabelAsymIds)
{
  const std::string path = mesolens_test::write_bytes(
    "assembly_label_asym.cif",
    mmcif_file("1 'author_defined_assembly'\n", "1 '(1,2)' A,B\n1 3 C\n",
               oper_row("1", mesolens::identity_assembly_matrix()) +
                 oper_row("2", rotation_z_90(0, 0, 10)) + oper_row("3", translation(100, 0, 0))));
  const mesolens::StructureFile file = mesolens::read_structure(path);
  EXPECT_TRUE(file.warnings.empty()) << file.warnings.front();
  const mesolens::AtomTable& unit = file.models.at(0);
  ASSERT_EQ(unit.size(), 8u);
  EXPECT_EQ(unit.label_asym_ids,
            (std::vector<std::string>{ "A", "A", "A", "A", "B", "B", "C", "C" }));
  EXPECT_EQ(unit.chain_ids[6], "A"); // the waters belong to author chain A
  ASSERT_EQ(file.assemblies.size(), 1u);
  const mesolens::Assembly& assembly = file.assemblies[0];
  EXPECT_EQ(assembly.details, "author_defined_assembly");
  ASSERT_EQ(assembly.generators.size(), 2u);
  EXPECT_EQ(assembly.generators[0].chain_ids, mesolens::AssemblyChainIds::Label);
  EXPECT_EQ(assembly.generators[1].chains, std::vector<std::string>{ "C" });
  EXPECT_EQ(mesolens::assembly_atom_count(unit, assembly), 14u);

  const mesolens::AssemblyExpansion expanded = mesolens::expand_assembly(unit, assembly);
  ASSERT_EQ(expanded.atoms.size(), 14u);
  EXPECT_NO_THROW(expanded.atoms.check_consistent());
  EXPECT_EQ(expanded.copy_of_atom, (std::vector<int>{ 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2 }));
  EXPECT_EQ(expanded.atoms.chain_ids,
            (std::vector<std::string>{ "A", "A", "A", "A", "B", "B", "A-2", "A-2", "A-2", "A-2",
                                       "B-2", "B-2", "A-3", "A-3" }));
  EXPECT_EQ(expanded.atoms.label_asym_ids[13], "C-3");
  // Copy 1 is Rz(90°) + 10 Å along z: atom 0 at (1, 0, 0) goes to (0, 1, 10).
  EXPECT_NEAR(expanded.atoms.positions[3 * 6 + 0], 0, 1e-5);
  EXPECT_NEAR(expanded.atoms.positions[3 * 6 + 1], 1, 1e-5);
  EXPECT_NEAR(expanded.atoms.positions[3 * 6 + 2], 10, 1e-5);
  EXPECT_NEAR(expanded.atoms.positions[3 * 12], 105, 1e-5);
  // Bonds within each copy (3 in chain A's glycine, 1 in B's), none in the waters' copy.
  ASSERT_EQ(unit.bonds.size(), 4u);
  ASSERT_EQ(expanded.atoms.bonds.size(), 8u);
  EXPECT_EQ(expanded.atoms.bonds[4].first, unit.bonds[0].first + 6);
  // Every copy has its own residues and molecules.
  EXPECT_EQ(
    std::set<int>(expanded.atoms.residue_indices.begin(), expanded.atoms.residue_indices.end())
      .size(),
    6u);
  EXPECT_NE(expanded.atoms.molecule_ids[0], expanded.atoms.molecule_ids[6]);
  EXPECT_FALSE(expanded.atoms.box.is_set());

  const mesolens::AssemblyInstances instances = mesolens::assembly_instances(unit, assembly);
  ASSERT_EQ(instances.atom_sets.size(), 2u);
  EXPECT_FALSE(instances.atom_sets[0].whole_table);
  EXPECT_EQ(instances.atom_sets[1].atoms, (std::vector<std::uint32_t>{ 6, 7 }));
  EXPECT_NEAR(instances.atom_sets[1].radius, 1.5, 1e-6);
  EXPECT_EQ(instances.instances[2].atom_set, 1u);
  EXPECT_NEAR(instances.instances[2].center[0], 106.5, 1e-6);
  expect_instances_match_expansion(unit, assembly, expanded);

  mesolens::AssemblyExpansionParams params;
  params.max_atoms = 13;
  try
  {
    mesolens::expand_assembly(unit, assembly, params);
    ADD_FAILURE() << "no error over the atom limit";
  }
  catch (const mesolens::InvalidInput& e)
  {
    EXPECT_NE(std::string(e.what()).find("14 atoms, more than the limit of 13"), std::string::npos)
      << e.what();
  }
  // With waters removed, the waters' copy is empty but still numbered.
  mesolens::StructureReadParams dry;
  dry.remove_waters = true;
  const mesolens::StructureFile dry_file = mesolens::read_structure(path, dry);
  EXPECT_EQ(mesolens::assembly_atom_count(dry_file.models[0], dry_file.assemblies[0]), 12u);
  EXPECT_EQ(
    mesolens::assembly_instances(dry_file.models[0], dry_file.assemblies[0]).instances.size(), 3u);
}

TEST(Assembly, AtomClassesFollowTheSetsHoldingEachAtom)
{
  // Sets over 8 rows: {0..5}, {6, 7}, {2, 3, 6}; row 4 appears in the first only, and so on.
  mesolens::AssemblyInstances instances;
  for (const std::vector<std::uint32_t>& rows :
       { std::vector<std::uint32_t>{ 0, 1, 2, 3, 4, 5 }, std::vector<std::uint32_t>{ 6, 7 },
         std::vector<std::uint32_t>{ 2, 3, 6 } })
  {
    mesolens::AssemblyAtomSet set;
    set.atoms = rows;
    instances.atom_sets.push_back(set);
  }
  for (const std::size_t set : { 0, 1, 2, 0 })
  {
    mesolens::AssemblyInstance copy;
    copy.atom_set = set;
    instances.instances.push_back(copy);
  }
  const mesolens::AssemblyAtomClasses classes = mesolens::assembly_atom_classes(instances, 9);
  // {0,1,4,5} in set 0 alone, {2,3} in 0 and 2, {6} in 1 and 2, {7} in 1, {8} in none.
  EXPECT_EQ(classes.count, 5u);
  EXPECT_EQ(classes.class_of_atom, (std::vector<std::uint32_t>{ 0, 0, 1, 1, 0, 0, 2, 3, 4 }));
  EXPECT_EQ(classes.in_set,
            (std::vector<std::uint8_t>{ 1, 0, 0, 1, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, 0 }));
  EXPECT_TRUE(classes.shows(instances, 3, 1));  // copy 3 uses set 0, which holds rows 2 and 3
  EXPECT_FALSE(classes.shows(instances, 2, 0)); // copy 2 uses set 2: not rows 0, 1, 4, 5
  EXPECT_FALSE(classes.shows(instances, 0, 4)); // row 8 is in no set
  // One set of every row: one class, shown by every copy.
  mesolens::AssemblyInstances whole;
  whole.atom_sets.resize(1);
  whole.atom_sets[0].atoms = { 0, 1, 2 };
  whole.instances.resize(60);
  const mesolens::AssemblyAtomClasses one = mesolens::assembly_atom_classes(whole, 3);
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.in_set, std::vector<std::uint8_t>{ 1 });
  // Copies of another table, or a copy naming a set that does not exist: refused.
  EXPECT_THROW(mesolens::assembly_atom_classes(whole, 2), mesolens::InvalidInput);
  whole.instances[5].atom_set = 1;
  EXPECT_THROW(mesolens::assembly_atom_classes(whole, 3), mesolens::InvalidInput);
  EXPECT_EQ(mesolens::assembly_atom_classes(mesolens::AssemblyInstances{}, 4).count, 1u);
}

TEST(Assembly, MalformedMmcifAssembliesAreLeftOutWithAWarning)
{
  std::string products;
  for (int i = 0; i < 20; ++i)
  {
    products += "(1,2)";
  }
  // author_defined_assembly: gemmi 0.5.7 would read these generators itself, and spend
  // minutes and gigabytes on (1-999999999) (read_structure keeps them from it).
  std::string assemblies;
  for (int id = 1; id <= 10; ++id)
  {
    assemblies += std::to_string(id) + " author_defined_assembly\n";
  }
  const std::string generators = "1 '(1,2)' A,B,C\n2 '(1-3)' A\n3 '(5-1)' A\n4 ? A\n5 '" +
    products + "' A\n6 '(1-999999999)' A\n7 '(1)(2' A\n8 9 A\n9 1 ?\n";
  AssemblyMatrix nan_matrix = mesolens::identity_assembly_matrix();
  nan_matrix[5] = std::nan("");
  std::string operators = oper_row("1", mesolens::identity_assembly_matrix()) +
    oper_row("2", rotation_z_90()) + oper_row("9", nan_matrix);
  const std::string path = mesolens_test::write_bytes(
    "assembly_malformed.cif", mmcif_file(assemblies, generators, operators));
  const auto start = std::chrono::steady_clock::now();
  const mesolens::StructureFile file = mesolens::read_structure(path);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(file.models.at(0).size(), 8u);
  ASSERT_EQ(file.assemblies.size(), 1u);
  EXPECT_EQ(file.assemblies[0].name, "1");
  EXPECT_EQ(file.assemblies[0].copy_count(), 2u);
  const std::pair<const char*, const char*> expected[] = {
    { "assembly '2'", "'3', which is not defined" },
    { "assembly '3'", "reversed range 5-1" },
    { "assembly '4'", "is empty" },
    { "assembly '5'", "1000000 copies at most are read from one file" },
    { "assembly '6'", "'3', which is not defined" },
    { "assembly '7'", "no ')'" },
    { "assembly '8'", "non-finite" },
    { "assembly '9'", "names no chain" },
    { "assembly '10'", "no operators" },
  };
  expect_warnings(file, expected);
}

// --- PDB REMARK 350 ------------------------------------------------------------------------

std::string atom_record(int serial, const char* name, const char* residue, char chain, int number,
                        double x, double y, double z, const char* element)
{
  char line[96];
  std::snprintf(line, sizeof line,
                "ATOM  %5d  %-3s %3s %c%4d    %8.3f%8.3f%8.3f  1.00 10.00          %2s\n", serial,
                name, residue, chain, number, x, y, z, element);
  return line;
}

std::string pdb_atoms()
{
  std::string text;
  int serial = 1;
  for (const char chain : { 'A', 'B', 'C' })
  {
    const double x = 10.0 * (chain - 'A');
    text += atom_record(serial++, "N", "GLY", chain, 1, x + 1.0, 0, 0, "N");
    text += atom_record(serial++, "CA", "GLY", chain, 1, x + 2.45, 0, 0, "C");
  }
  return text + "END\n";
}

TEST(Assembly, PdbChainContinuationsAndShiftedSerials)
{
  const std::string remarks =
    "REMARK 350 BIOMOLECULE: 1                                                       \n"
    "REMARK 350 AUTHOR DETERMINED BIOLOGICAL UNIT: TRIMERIC                          \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A, B,                                 \n"
    "REMARK 350                    AND CHAINS: C                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350   BIOMT1  1000  0.000000 -1.000000  0.000000     -171.60935          \n"
    "REMARK 350   BIOMT2  1000  1.000000  0.000000  0.000000       11.07467          \n"
    "REMARK 350   BIOMT3  1000  0.000000  0.000000  1.000000        0.50000          \n"
    "REMARK 350 BIOMOLECULE: 2                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: B, C                                  \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000       20.00000            \n";
  const std::string path =
    mesolens_test::write_bytes("assembly_continuations.pdb", remarks + pdb_atoms());
  const mesolens::StructureFile file = mesolens::read_structure(path);
  ASSERT_EQ(file.models.at(0).size(), 6u);
  EXPECT_TRUE(file.warnings.empty()) << file.warnings.front();
  ASSERT_EQ(file.assemblies.size(), 2u);
  const mesolens::Assembly& assembly = file.assemblies[0];
  EXPECT_EQ(assembly.details, "AUTHOR DETERMINED BIOLOGICAL UNIT: TRIMERIC");
  ASSERT_EQ(assembly.generators.size(), 1u);
  EXPECT_EQ(assembly.generators[0].chains, (std::vector<std::string>{ "A", "B", "C" }));
  EXPECT_EQ(assembly.generators[0].chain_ids, mesolens::AssemblyChainIds::Author);
  ASSERT_EQ(assembly.generators[0].operators.size(), 2u);
  EXPECT_EQ(assembly.generators[0].operators[1].name, "1000");
  expect_near(assembly.generators[0].operators[1].matrix, rotation_z_90(-171.60935, 11.07467, 0.5));
  const mesolens::AssemblyExpansion expanded = mesolens::expand_assembly(file.models[0], assembly);
  EXPECT_EQ(expanded.atoms.size(), 12u);
  EXPECT_EQ(expanded.atoms.chain_ids[11], "C-2");
  expect_instances_match_expansion(file.models[0], assembly, expanded);
  const auto instances = mesolens::assembly_instances(file.models[0], assembly);
  ASSERT_EQ(instances.atom_sets.size(), 1u);
  EXPECT_TRUE(instances.atom_sets[0].whole_table);
  // Two generators: chain A as it is (copy 0), chains B and C 20 Å up (copy 1).
  const mesolens::Assembly& two = file.assemblies[1];
  ASSERT_EQ(two.generators.size(), 2u);
  EXPECT_EQ(two.generators[1].chains, (std::vector<std::string>{ "B", "C" }));
  const mesolens::AssemblyExpansion parts = mesolens::expand_assembly(file.models[0], two);
  EXPECT_EQ(parts.atoms.chain_ids,
            (std::vector<std::string>{ "A", "A", "B-2", "B-2", "C-2", "C-2" }));
  EXPECT_NEAR(parts.atoms.positions[3 * 5 + 2], 20, 1e-5);
  expect_instances_match_expansion(file.models[0], two, parts);
}

TEST(Assembly, PdbRemarksAreReadWhereverTheyStandBeforeEnd)
{
  const std::string identity =
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000\r\n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000\r\n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000\r\n";
  std::string atoms = pdb_atoms();
  atoms.erase(atoms.size() - 4); // "END\n"
  // The second assembly's records follow the atoms (CRLF lines, lower-case record names); a
  // third one after END is not read, as gemmi reads nothing after END.
  const std::string text = "REMARK 350 BIOMOLECULE: 1\r\n"
                           "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A\r\n" +
    identity + atoms +
    "remark 350 BIOMOLECULE: 2\r\n"
    "remark 350 APPLY THE FOLLOWING TO CHAINS: B, C\r\n" +
    identity +
    "END\r\nREMARK 350 BIOMOLECULE: 3\r\nREMARK 350 APPLY THE FOLLOWING TO CHAINS: A\r\n" +
    identity;
  const std::string path = mesolens_test::write_bytes("assembly_remarks_after_atoms.pdb", text);
  const mesolens::StructureFile file = mesolens::read_structure(path);
  ASSERT_EQ(file.models.at(0).size(), 6u);
  EXPECT_TRUE(file.warnings.empty()) << file.warnings.front();
  ASSERT_EQ(file.assemblies.size(), 2u);
  EXPECT_EQ(file.assemblies[1].name, "2");
  ASSERT_EQ(file.assemblies[1].generators.size(), 1u);
  EXPECT_EQ(file.assemblies[1].generators[0].chains, (std::vector<std::string>{ "B", "C" }));
  EXPECT_EQ(file.assemblies[1].generators[0].operators.size(), 1u);
}

TEST(Assembly, MalformedPdbAssembliesAreLeftOutWithAWarning)
{
  const std::string remarks =
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 1                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A, B, C                               \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 2                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 3                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1       nan  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 4                                                       \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 5                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1  1.0000x0  0.000000  0.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 6                                                       \n"
    "REMARK 350                    AND CHAINS: A                                     \n"
    "REMARK 350 BIOMOLECULE: 7                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   2  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 8                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: Q                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n"
    "REMARK 350 BIOMOLECULE: 1                                                       \n"
    "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A                                     \n"
    "REMARK 350   BIOMT1   1  1.000000  0.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT2   1  0.000000  1.000000  0.000000        0.00000            \n"
    "REMARK 350   BIOMT3   1  0.000000  0.000000  1.000000        0.00000            \n";
  const std::string path =
    mesolens_test::write_bytes("assembly_malformed.pdb", remarks + pdb_atoms());
  const mesolens::StructureFile file = mesolens::read_structure(path);
  EXPECT_EQ(file.models.at(0).size(), 6u);
  ASSERT_EQ(file.assemblies.size(), 2u);
  EXPECT_EQ(file.assemblies[0].name, "1");
  EXPECT_EQ(file.assemblies[1].name, "8"); // kept: it names a chain the file lacks
  EXPECT_EQ(mesolens::assembly_atom_count(file.models[0], file.assemblies[1]), 0u);
  const std::pair<const char*, const char*> expected[] = {
    { "1 REMARK 350 chain or BIOMT lines", "before any BIOMOLECULE" },
    { "assembly '2'", "BIOMT3 of operator 1 out of order (line 10)" },
    { "assembly '3'", "non-finite" },
    { "assembly '4'", "before any APPLY THE FOLLOWING TO CHAINS" },
    { "assembly '5'", "not 'BIOMTn serial m1 m2 m3 t'" },
    { "assembly '6'", "AND CHAINS line that continues no chain list" },
    { "assembly '7'", "BIOMT2 of operator 2 out of order" },
    { "assembly '8'", "names 1 chains the file does not have (Q)" },
    { "assembly '1'", "name of an earlier assembly" },
  };
  expect_warnings(file, expected);
}

// --- real files against gemmi --------------------------------------------------------------

std::size_t gemmi_atoms(const gemmi::Model& model)
{
  std::size_t count = 0;
  for (const gemmi::Chain& chain : model.chains)
  {
    for (const gemmi::Residue& residue : chain.residues)
    {
      count += residue.atoms.size();
    }
  }
  return count;
}

/// gemmi's make_assembly count; counted from the same selection rule without building the
/// atoms when the assembly is large (1m4x.pdb: 16 million atoms).
std::size_t gemmi_assembly_atoms(const gemmi::Assembly& assembly, const gemmi::Model& model)
{
  std::size_t copies = 0;
  for (const auto& generator : assembly.generators)
  {
    copies += generator.operators.size();
  }
  if (copies * gemmi_atoms(model) <= 2000000)
  {
    return gemmi_atoms(
      gemmi::make_assembly(assembly, model, gemmi::HowToNameCopiedChain::Dup, nullptr));
  }
  std::size_t count = 0;
  for (const auto& generator : assembly.generators)
  {
    std::size_t selected = 0;
    for (const gemmi::Chain& chain : model.chains)
    {
      const bool whole = gemmi::in_vector(chain.name, generator.chains);
      for (const gemmi::Residue& residue : chain.residues)
      {
        if (whole || gemmi::in_vector(residue.subchain, generator.subchains))
        {
          selected += residue.atoms.size();
        }
      }
    }
    count += selected * generator.operators.size();
  }
  return count;
}

/// Compares every assembly gemmi finds in the folder's PDB and mmCIF files with ours; returns
/// how many were compared.
std::size_t compare_folder_with_gemmi(const std::string& folder)
{
  std::size_t compared = 0;
  std::set<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
  {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && (extension == ".pdb" || extension == ".cif"))
    {
      paths.insert(entry.path().string());
    }
  }
  for (const std::string& path : paths)
  {
    gemmi::Structure reference;
    try
    {
      reference = gemmi::read_structure(gemmi::MaybeGzipped(path));
    }
    catch (const std::exception&)
    {
      continue; // gemmi alone cannot read it (1hpv.pdb): no oracle
    }
    const mesolens::StructureFile ours = read_all_atoms(path);
    const bool is_1m4x_cif = path.size() >= 8 && path.compare(path.size() - 8, 8, "1m4x.cif") == 0;
    if (!is_1m4x_cif)
    {
      EXPECT_EQ(ours.assemblies.size(), reference.assemblies.size()) << path;
    }
    const std::size_t unit = gemmi_atoms(reference.models.at(0));
    EXPECT_EQ(ours.models.at(0).size(), unit) << path;
    for (const gemmi::Assembly& assembly : reference.assemblies)
    {
      const mesolens::Assembly* mine = mesolens::find_assembly(ours.assemblies, assembly.name);
      if (!mine)
      {
        ADD_FAILURE() << path << ": no assembly " << assembly.name;
        continue;
      }
      const std::size_t count = mesolens::assembly_atom_count(ours.models[0], *mine);
      if (is_1m4x_cif)
      {
        continue; // gemmi expands 60 of 1680 operators: see Mmcif1m4xProductIsThePdbBiomtList
      }
      EXPECT_EQ(count, gemmi_assembly_atoms(assembly, reference.models[0]))
        << path << " assembly " << assembly.name;
      std::printf("%s assembly %s: %zu atoms (asymmetric unit %zu), gemmi the same\n",
                  std::filesystem::path(path).filename().c_str(), assembly.name.c_str(), count,
                  unit);
      if (count <= 400000)
      {
        EXPECT_EQ(mesolens::expand_assembly(ours.models[0], *mine).atoms.size(), count) << path;
      }
      ++compared;
    }
  }
  return compared;
}

TEST(Assembly, AtomCountsEqualGemmiOnData)
{
  EXPECT_GE(compare_folder_with_gemmi(mesolens_test::data_file("proteins")), 13u);
}

TEST(Assembly, AtomCountsEqualGemmiOnSharedData)
{
  const std::string folder = mesolens_test::shared_file("proteins");
  if (!mesolens_test::exists(folder + "/1rb8.pdb"))
    GTEST_SKIP() << "needs ../shared/data/proteins";
  EXPECT_GE(compare_folder_with_gemmi(folder), 20u);
}

TEST(Assembly, PhiX174CapsidExpandsTo60Copies)
{
  const std::string path = mesolens_test::shared_file("proteins/1rb8.pdb");
  if (!mesolens_test::exists(path))
    GTEST_SKIP() << "needs ../shared/data/proteins";
  const mesolens::StructureFile file = mesolens::read_structure(path);
  const mesolens::AtomTable& unit = file.models.at(0);
  const mesolens::Assembly* assembly = mesolens::find_assembly(file.assemblies, "1");
  ASSERT_NE(assembly, nullptr);
  ASSERT_EQ(assembly->copy_count(), 60u);
  const auto start = std::chrono::steady_clock::now();
  const mesolens::AssemblyExpansion expanded = mesolens::expand_assembly(unit, *assembly);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("1rb8: %zu atoms expanded to %zu in %.3f s\n", unit.size(), expanded.atoms.size(),
              seconds);
  ASSERT_EQ(expanded.atoms.size(), 60 * unit.size());
  EXPECT_NO_THROW(expanded.atoms.check_consistent());
  EXPECT_EQ(expanded.atoms.bonds.size(), 60 * unit.bonds.size());
  EXPECT_EQ(expanded.atoms.residue_indices.back() + 1, 60 * (unit.residue_indices.back() + 1));
  EXPECT_EQ(expanded.atoms.chain_ids.back(), unit.chain_ids.back() + "-60");
  expect_instances_match_expansion(unit, *assembly, expanded);
}

TEST(Assembly, Mmcif1m4xProductIsThePdbBiomtList)
{
  const std::string pdb_path = mesolens_test::shared_file("proteins/1m4x.pdb");
  const std::string cif_path = mesolens_test::shared_file("proteins/1m4x.cif");
  if (!mesolens_test::exists(pdb_path) || !mesolens_test::exists(cif_path))
    GTEST_SKIP() << "needs ../shared/data/proteins";
  const mesolens::StructureFile pdb = read_all_atoms(pdb_path);
  const mesolens::StructureFile cif = read_all_atoms(cif_path);
  const mesolens::Assembly* from_pdb = mesolens::find_assembly(pdb.assemblies, "1");
  const mesolens::Assembly* from_cif = mesolens::find_assembly(cif.assemblies, "1");
  ASSERT_TRUE(from_pdb && from_cif);
  EXPECT_EQ(cif.assemblies.size(), 7u); // 1-6 and PAU
  ASSERT_EQ(from_cif->generators.size(), 1u);
  const auto& biomt = from_pdb->generators.at(0).operators;
  const auto& product = from_cif->generators[0].operators;
  ASSERT_EQ(biomt.size(), 1680u);
  ASSERT_EQ(product.size(), 1680u);
  // (1-60)(61-88) in order, M_i·M_j, is the BIOMT list to its printed digits (serials past 99
  // are pushed right in the PDB file: read by column, as gemmi 0.5.7 does, they give garbage).
  for (std::size_t c = 0; c < product.size(); ++c)
  {
    for (std::size_t k = 0; k < 12; ++k)
    {
      ASSERT_NEAR(product[c].matrix[k], biomt[c].matrix[k], k % 4 == 3 ? 1e-4 : 1e-5)
        << "copy " << c << " (" << product[c].name << ", BIOMT " << biomt[c].name << ")";
    }
  }
  const std::size_t atoms = mesolens::assembly_atom_count(pdb.models.at(0), *from_pdb);
  EXPECT_EQ(atoms, 1680u * pdb.models[0].size());
  EXPECT_EQ(mesolens::assembly_atom_count(cif.models.at(0), *from_cif), atoms);
  std::printf("1m4x: %zu atoms from the PDB BIOMT list and from the mmCIF product\n", atoms);
  const mesolens::AssemblyInstances instances =
    mesolens::assembly_instances(cif.models[0], *from_cif);
  EXPECT_EQ(instances.instances.size(), 1680u);
  ASSERT_EQ(instances.atom_sets.size(), 1u);
  EXPECT_TRUE(instances.atom_sets[0].whole_table);
  // Too many atoms for a small limit: refused before anything is allocated.
  mesolens::AssemblyExpansionParams params;
  params.max_atoms = 1000000;
  EXPECT_THROW(mesolens::expand_assembly(cif.models[0], *from_cif, params), mesolens::InvalidInput);
  // A smaller assembly of the same file: "(61-88)", the icosahedral asymmetric unit.
  const mesolens::Assembly* unit_of_28 = mesolens::find_assembly(cif.assemblies, "2");
  ASSERT_NE(unit_of_28, nullptr);
  const mesolens::AssemblyExpansion expanded =
    mesolens::expand_assembly(cif.models[0], *unit_of_28);
  EXPECT_EQ(expanded.atoms.size(), 28 * cif.models[0].size());
  expect_instances_match_expansion(cif.models[0], *unit_of_28, expanded);
}

} // namespace

TEST(Assembly, RotationsAsQuaternions)
{
  const double half = std::sqrt(0.5);
  // 90 degrees about z: (cos 45, 0, 0, sin 45).
  const mesolens::AssemblyMatrix quarter = { 0, -1, 0, 5, 1, 0, 0, 6, 0, 0, 1, 7 };
  const auto q = mesolens::rotation_quaternion(quarter);
  EXPECT_NEAR(q[0], half, 1e-12);
  EXPECT_NEAR(q[1], 0.0, 1e-12);
  EXPECT_NEAR(q[2], 0.0, 1e-12);
  EXPECT_NEAR(q[3], half, 1e-12);
  // 180 degrees about x keeps w = 0; the identity gives (1, 0, 0, 0).
  const auto flip = mesolens::rotation_quaternion({ 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 0 });
  EXPECT_NEAR(std::abs(flip[1]), 1.0, 1e-12);
  EXPECT_EQ(mesolens::rotation_quaternion(mesolens::identity_assembly_matrix())[0], 1.0);
  // The quaternion's matrix is R again, for a BIOMT-like rotation written with six decimals.
  const mesolens::AssemblyMatrix written = { 0.309017, -0.809017, 0.5,  0,        0.809017, 0.5,
                                             0.309017, 0,         -0.5, 0.309017, 0.809017, 0 };
  const auto r = mesolens::rotation_quaternion(written);
  const double w = r[0], x = r[1], y = r[2], z = r[3];
  const double back[9] = {
    1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
    2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
    2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)
  };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_NEAR(back[3 * i + j], written[std::size_t(4 * i + j)], 1e-5);
    }
  }
  EXPECT_GE(r[0], 0.0);
  // A reflection, a scaling and NaN are no rotations.
  EXPECT_THROW(mesolens::rotation_quaternion({ -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::rotation_quaternion({ 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::rotation_quaternion({ NAN, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 }),
               mesolens::InvalidInput);
}
