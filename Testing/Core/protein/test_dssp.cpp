// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/dssp.h"
#include "mesolens/common/errors.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/protein/ribbon_trace.h"
#include "mesolens_test_data.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using mesolens::SecondaryStructure;

namespace {
/// Fraction of positions where two strings of one length agree.
double agreement(const std::string& a, const std::string& b)
{
  if (a.size() != b.size() || a.empty())
    return 0.0;
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    same += a[i] == b[i];
  return double(same) / double(a.size());
}

/// The backbone of a structure file's first model (or `model`).
mesolens::ProteinBackbone backbone_of(const std::string& path, std::size_t model = 0)
{
  const auto file = mesolens::read_structure(path);
  return mesolens::protein_backbone(file.models.at(model));
}

/// Per chain, the assignment as letters ('-' coil).
std::vector<std::string> chain_strings(const mesolens::ProteinBackbone& backbone,
                                       const mesolens::DsspResult& result)
{
  std::vector<std::string> chains;
  for (std::size_t r = 0; r < backbone.residues.size(); ++r)
  {
    if (r == 0 || backbone.residues[r].chain != backbone.residues[r - 1].chain)
      chains.emplace_back();
    chains.back() += mesolens::dssp_string({ result.structure[r] });
  }
  return chains;
}

/// An ideal backbone with the given phi/psi (degrees) for `count` residues (standard bond
/// lengths and angles, trans peptides), built atom by atom.
std::vector<mesolens::BackboneResidue> ideal_backbone(int count, double phi, double psi)
{
  using V = std::array<double, 3>;
  auto sub = [](V a, V b) { return V{ a[0] - b[0], a[1] - b[1], a[2] - b[2] }; };
  auto cross = [](V a, V b) {
    return V{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
  };
  auto unit = [](V a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return V{ a[0] / l, a[1] / l, a[2] / l };
  };
  // Places d from c with bond length, angle b-c-d and dihedral a-b-c-d (degrees).
  auto place = [&](V a, V b, V c, double length, double angle, double torsion) {
    const double t = angle * M_PI / 180.0;
    const double p = torsion * M_PI / 180.0;
    const V bc = unit(sub(c, b));
    const V n = unit(cross(sub(b, a), bc));
    const V m = cross(n, bc);
    const V d2{ -length * std::cos(t), length * std::sin(t) * std::cos(p),
                length * std::sin(t) * std::sin(p) };
    return V{ c[0] + d2[0] * bc[0] + d2[1] * m[0] + d2[2] * n[0],
              c[1] + d2[0] * bc[1] + d2[1] * m[1] + d2[2] * n[1],
              c[2] + d2[0] * bc[2] + d2[1] * m[2] + d2[2] * n[2] };
  };
  std::vector<mesolens::BackboneResidue> residues;
  V n{ 0, 0, 0 }, ca{ 1.458, 0, 0 }, c = place({ 0, 1, 0 }, n, ca, 1.525, 111.0, -60.0);
  for (int i = 0; i < count; ++i)
  {
    mesolens::BackboneResidue r;
    r.n = n;
    r.ca = ca;
    r.c = c;
    const V next_n = place(n, ca, c, 1.329, 116.2, psi);
    r.o = place(next_n, ca, c, 1.231, 120.5, 180.0);
    r.has_n = r.has_ca = r.has_c = r.has_o = true;
    residues.push_back(r);
    const V next_ca = place(ca, c, next_n, 1.458, 121.7, 180.0);
    const V next_c = place(c, next_n, next_ca, 1.525, 111.0, phi);
    n = next_n;
    ca = next_ca;
    c = next_c;
  }
  return residues;
}
} // namespace

TEST(Dssp, LettersRoundTrip)
{
  for (char letter : std::string("HGIEBTSP"))
    EXPECT_EQ(mesolens::dssp_letter(mesolens::from_dssp_letter(letter)), letter);
  EXPECT_EQ(mesolens::from_dssp_letter('-'), SecondaryStructure::Coil);
  EXPECT_EQ(mesolens::dssp_letter(SecondaryStructure::Coil), ' ');
}

TEST(Dssp, AnIdealAlphaHelixIsAHelixAndAStrandIsNot)
{
  const auto helix = ideal_backbone(20, -57.0, -47.0);
  const auto result = mesolens::assign_secondary_structure(helix);
  const std::string letters = mesolens::dssp_string(result.structure);
  // i -> i+4 bonds from residue 0: H from residue 1 to 18 (the first and last are no part).
  EXPECT_EQ(letters.substr(1, 18), std::string(18, 'H')) << letters;
  EXPECT_GE(result.hydrogen_bonds, 15u);
  // A single extended chain has no partner: no strand, no helix.
  const auto extended = mesolens::assign_secondary_structure(ideal_backbone(12, -120.0, 130.0));
  const std::string straight = mesolens::dssp_string(extended.structure);
  EXPECT_EQ(straight.find_first_of("HGIEB"), std::string::npos) << straight;
  // Polyproline II angles make a kappa helix (DSSP 4), or nothing in the classic mode.
  const auto pp = ideal_backbone(8, -75.0, 145.0);
  EXPECT_NE(mesolens::dssp_string(mesolens::assign_secondary_structure(pp).structure).find("PPP"),
            std::string::npos);
  mesolens::DsspParams classic;
  classic.polyproline_stretch = 0;
  EXPECT_EQ(
    mesolens::dssp_string(mesolens::assign_secondary_structure(pp, classic).structure).find('P'),
    std::string::npos);
}

TEST(Dssp, CrambinAgreesWithMkdssp)
{
  // mkdssp 4.2.2 on 1crn (../shared/data/reference/generated/mkdssp_ss_strings.tsv).
  const std::string reference = "-EE-SSHHHHHHHHHHHTTT--HHHHHHHHS-EE-SSS---GGG--";
  const auto backbone = backbone_of(mesolens_test::data_file("proteins/1crn.pdb"));
  ASSERT_EQ(backbone.residues.size(), reference.size());
  const auto result = mesolens::assign_secondary_structure(backbone.residues);
  const std::string ours = mesolens::dssp_string(result.structure);
  std::printf("1crn  mkdssp %s\n      ours   %s  agreement %.3f\n", reference.c_str(), ours.c_str(),
              agreement(ours, reference));
  EXPECT_GE(agreement(ours, reference), 0.95);
  // The same from mmCIF, and on two threads.
  const auto cif = backbone_of(mesolens_test::data_file("proteins/1crn.cif"));
  const auto two_threads = mesolens_test::two_threads();
  EXPECT_EQ(mesolens::dssp_string(
              mesolens::assign_secondary_structure(cif.residues, {}, two_threads).structure),
            ours);
}

TEST(Dssp, AgreesWithMkdsspOnEveryReferenceFile)
{
  const std::string table = mesolens_test::shared_file("reference/generated/mkdssp_ss_strings.tsv");
  if (!mesolens_test::exists(table))
    GTEST_SKIP() << "needs ../shared/data";
  std::ifstream lines(table);
  std::map<std::string, std::vector<std::pair<std::string, std::string>>>
    chains; // id -> (chain, ss)
  std::string line;
  while (std::getline(lines, line))
  {
    if (line.empty() || line[0] == '#' || line.rfind("id\t", 0) == 0)
      continue;
    std::istringstream fields(line);
    std::string id, chain, count, ss;
    std::getline(fields, id, '\t');
    std::getline(fields, chain, '\t');
    std::getline(fields, count, '\t');
    std::getline(fields, ss, '\t');
    chains[id].emplace_back(chain, ss);
  }
  ASSERT_GE(chains.size(), 10u);
  for (const auto& [id, expected] : chains)
  {
    std::string path = mesolens_test::shared_file("proteins/" + id + ".cif");
    if (!mesolens_test::exists(path))
      path = mesolens_test::shared_file("proteins/" + id + ".pdb");
    const auto backbone = backbone_of(path);
    const auto result = mesolens::assign_secondary_structure(backbone.residues);
    // mkdssp leaves chain breaks out of its strings; compare over all chains joined.
    std::string ours_all;
    for (const std::string& chain : chain_strings(backbone, result))
      ours_all += chain;
    std::string reference_all;
    for (const auto& [chain, ss] : expected)
      reference_all += ss;
    const double fraction = agreement(ours_all, reference_all);
    std::printf("%-5s %zu chains, %zu residues (mkdssp %zu): agreement %.4f\n", id.c_str(),
                expected.size(), ours_all.size(), reference_all.size(), fraction);
    EXPECT_EQ(ours_all.size(), reference_all.size()) << id;
    EXPECT_GE(fraction, 0.95) << id;
  }
}

namespace {
/// The 8-state letters of a classic DSSP output (one per residue line, '!' breaks skipped,
/// ' ' as '-').
std::string classic_dssp_letters(const std::string& path)
{
  std::ifstream lines(path);
  std::string line;
  bool residues = false;
  std::string letters;
  while (std::getline(lines, line))
  {
    if (line.rfind("  #  RESIDUE", 0) == 0)
    {
      residues = true;
      continue;
    }
    if (!residues || line.size() < 17 || line[13] == '!')
      continue;
    letters += line[16] == ' ' ? '-' : line[16];
  }
  return letters;
}
} // namespace

TEST(Dssp, AgreesWithClassicDsspOnEveryModel)
{
  // DSSP 2.0 ("CMBI version 2010-10-21") outputs from MDTraj's tests: alpha before pi, no
  // polyproline helices.
  const std::string folder = mesolens_test::shared_file("reference/dssp_mdtraj/");
  if (!mesolens_test::exists(folder + "1bpi.pdb"))
    GTEST_SKIP() << "needs ../shared/data";
  mesolens::DsspParams classic;
  classic.pi_helix_priority = false;
  classic.polyproline_stretch = 0;
  const auto bpti = backbone_of(folder + "1bpi.pdb");
  const std::string bpti_ours =
    mesolens::dssp_string(mesolens::assign_secondary_structure(bpti.residues, classic).structure);
  const std::string bpti_reference = classic_dssp_letters(folder + "1bpi.pdb_0.dssp");
  std::printf("1bpi  agreement %.4f\n", agreement(bpti_ours, bpti_reference));
  EXPECT_GE(agreement(bpti_ours, bpti_reference), 0.95);
  // 2EQQ, an NMR ensemble of 20 models, each against its own reference.
  const auto ensemble = mesolens::read_structure(folder + "2EQQ.pdb");
  ASSERT_EQ(ensemble.models.size(), 20u);
  double worst = 1.0;
  for (std::size_t m = 0; m < 20; ++m)
  {
    const auto backbone = mesolens::protein_backbone(ensemble.models[m]);
    const std::string ours = mesolens::dssp_string(
      mesolens::assign_secondary_structure(backbone.residues, classic).structure);
    const std::string reference =
      classic_dssp_letters(folder + "2EQQ.pdb_" + std::to_string(m) + ".dssp");
    worst = std::min(worst, agreement(ours, reference));
    EXPECT_GE(agreement(ours, reference), 0.95) << "model " << m << "\n"
                                                << ours << "\n"
                                                << reference;
  }
  std::printf("2EQQ  20 models, worst agreement %.4f\n", worst);
}

TEST(Dssp, AgreesWithMDAnalysisThreeStates)
{
  // MDAnalysis' DSSP oracle: one-line H/E/- strings for 10 header-less chains (helices of
  // every kind as H, strands and bridges as E). That method (PyDSSP's) joins no ladders across
  // bulges: compared with the same setting; with bulges, 1h4aX differs in its long sheets.
  mesolens::DsspParams pydssp;
  pydssp.bulges = false;
  const std::string folder = mesolens_test::shared_file("reference/dssp_mdanalysis/");
  if (!mesolens_test::exists(folder + "1ahsA.pdb"))
    GTEST_SKIP() << "needs ../shared/data";
  for (const char* id :
       { "1ahsA", "1bvyF", "1eteA", "1h4aX", "1lpbA", "1mr1D", "2xdgA", "3e8mA", "3gfsA", "4dkcA" })
  {
    std::ifstream file(folder + id + ".pdb.dssp");
    std::string reference;
    file >> reference;
    const auto backbone = backbone_of(folder + id + ".pdb");
    const auto result = mesolens::assign_secondary_structure(backbone.residues, pydssp);
    std::string ours;
    for (SecondaryStructure s : result.structure)
    {
      const char letter = mesolens::dssp_letter(s);
      ours += letter == 'H' || letter == 'G' || letter == 'I' ? 'H'
        : letter == 'E' || letter == 'B'                      ? 'E'
                                                              : '-';
    }
    std::printf("%s %zu residues: agreement %.4f\n", id, ours.size(), agreement(ours, reference));
    EXPECT_EQ(ours.size(), reference.size()) << id;
    EXPECT_GE(agreement(ours, reference), 0.95) << id << "\n" << ours << "\n" << reference;
  }
}

TEST(Dssp, WithTheConformerMkdsspTakesAlternatesAgreeExactly)
{
  // At equal occupancy mkdssp 4.2.2 keeps the second conformer (B), the readers the first: the
  // only difference left on 3o5r and 4we2.
  for (const char* id : { "3o5r", "4we2" })
  {
    std::string path = mesolens_test::shared_file(std::string("proteins/") + id + ".cif");
    if (!mesolens_test::exists(path))
      path = mesolens_test::shared_file(std::string("proteins/") + id + ".pdb");
    if (!mesolens_test::exists(path))
      GTEST_SKIP() << "needs ../shared/data";
    mesolens::StructureReadParams all;
    all.alt_locs = mesolens::AltLocPolicy::KeepAll;
    auto table = mesolens::read_structure(path, all).models.at(0);
    std::vector<bool> keep(table.size());
    for (std::size_t i = 0; i < table.size(); ++i)
      keep[i] = table.alt_locs[i] != 'A';
    table.filter(keep);
    const auto backbone = mesolens::protein_backbone(table);
    const std::string ours =
      mesolens::dssp_string(mesolens::assign_secondary_structure(backbone.residues).structure);
    std::ifstream lines(mesolens_test::shared_file("reference/generated/mkdssp_ss_strings.tsv"));
    std::string line, reference;
    while (std::getline(lines, line))
      if (line.rfind(std::string(id) + "\t", 0) == 0)
        reference = line.substr(line.rfind('\t') + 1);
    EXPECT_EQ(ours, reference) << id;
  }
}

TEST(Dssp, HydrogensPresentOrAbsentGiveTheSameAnswer)
{
  // Trp-cage (NMR, explicit hydrogens): the placed amide H, the file's H, and the file without
  // any hydrogen give one assignment; each of its 38 models is assigned.
  const auto file = mesolens::read_structure(mesolens_test::data_file("proteins/1l2y.pdb"));
  ASSERT_EQ(file.models.size(), 38u);
  const auto backbone = mesolens::protein_backbone(file.models[0]);
  ASSERT_TRUE(backbone.residues[5].has_h);
  const std::string placed =
    mesolens::dssp_string(mesolens::assign_secondary_structure(backbone.residues).structure);
  EXPECT_EQ(placed, "-HHHHHHHTTGGGGT-PPP-"); // mkdssp 4.2.2
  mesolens::DsspParams with_file_h;
  with_file_h.file_hydrogens = true;
  const std::string from_file = mesolens::dssp_string(
    mesolens::assign_secondary_structure(backbone.residues, with_file_h).structure);
  EXPECT_GE(agreement(from_file, placed), 0.9) << from_file;
  mesolens::StructureReadParams no_h;
  no_h.remove_hydrogens = true;
  const auto stripped = mesolens::protein_backbone(
    mesolens::read_structure(mesolens_test::data_file("proteins/1l2y.pdb"), no_h).models[0]);
  EXPECT_FALSE(stripped.residues[5].has_h);
  EXPECT_EQ(
    mesolens::dssp_string(mesolens::assign_secondary_structure(stripped.residues).structure),
    placed);
  std::size_t helical_models = 0;
  for (const auto& model : file.models)
  {
    const auto result =
      mesolens::assign_secondary_structure(mesolens::protein_backbone(model).residues);
    ASSERT_EQ(result.structure.size(), 20u);
    helical_models += result.structure[4] == SecondaryStructure::AlphaHelix;
  }
  EXPECT_GE(helical_models, 35u); // the helix is stable across the ensemble
}

TEST(Dssp, FilesMkdsspRefusesGetAFullAssignment)
{
  // 1hpv (no element column, blank chains) and 1tii (a header date mkdssp rejects): every
  // residue assigned; the helices and strands of the HELIX/SHEET records are found.
  for (const char* id : { "1hpv", "1tii" })
  {
    const auto table =
      mesolens::read_structure(mesolens_test::data_file(std::string("proteins/") + id + ".pdb"))
        .models.at(0);
    const auto backbone = mesolens::protein_backbone(table);
    const auto result = mesolens::assign_secondary_structure(backbone.residues);
    ASSERT_GT(backbone.residues.size(), 150u) << id;
    // Residues the file calls helix or strand, and how many of them DSSP agrees with.
    std::size_t recorded = 0, agreed = 0;
    for (std::size_t r = 0; r < backbone.residues.size(); ++r)
    {
      std::size_t atom = 0;
      while (table.residue_indices[atom] != backbone.residue_index[r])
        ++atom;
      const auto file_class = SecondaryStructure(table.secondary_structure[atom]);
      const char ours = mesolens::dssp_letter(result.structure[r]);
      if (file_class == SecondaryStructure::AlphaHelix)
      {
        ++recorded;
        agreed += ours == 'H' || ours == 'G' || ours == 'I';
      }
      else if (file_class == SecondaryStructure::Strand)
      {
        ++recorded;
        agreed += ours == 'E' || ours == 'B';
      }
    }
    std::printf("%s: %zu residues, %zu in HELIX/SHEET records, %.3f of them agree\n", id,
                backbone.residues.size(), recorded, double(agreed) / double(recorded));
    EXPECT_GT(recorded, 20u) << id;
    EXPECT_GE(double(agreed) / double(recorded), 0.85) << id;
  }
}

TEST(Dssp, MissingBackboneAtomsBreakTheChain)
{
  auto helix = ideal_backbone(24, -57.0, -47.0);
  helix[12].has_o = false; // a residue without its carbonyl O
  const auto result = mesolens::assign_secondary_structure(helix);
  EXPECT_EQ(result.structure[12], SecondaryStructure::Coil);
  EXPECT_EQ(result.break_before[12], 1);
  EXPECT_EQ(result.break_before[13], 1);
  EXPECT_EQ(mesolens::dssp_letter(result.structure[5]), 'H');
  EXPECT_EQ(mesolens::dssp_letter(result.structure[18]), 'H');
  // A long peptide bond breaks the chain too.
  auto split = ideal_backbone(24, -57.0, -47.0);
  for (std::size_t r = 12; r < split.size(); ++r)
    for (auto* atom : { &split[r].n, &split[r].ca, &split[r].c, &split[r].o })
      (*atom)[0] += 30.0;
  const auto apart = mesolens::assign_secondary_structure(split);
  EXPECT_EQ(apart.break_before[12], 1);
  // Two chains: residues of another chain never pair along the chain.
  auto two = ideal_backbone(24, -57.0, -47.0);
  for (std::size_t r = 12; r < two.size(); ++r)
    two[r].chain = 1;
  EXPECT_EQ(mesolens::assign_secondary_structure(two).break_before[12], 1);
}

TEST(Dssp, CaOnlyChainsAreAssignedFromTheirCaGeometry)
{
  // Crambin's Cα alone: its two helices and its small sheet are found from the Cα trace.
  const auto backbone = backbone_of(mesolens_test::data_file("proteins/1crn.pdb"));
  std::vector<mesolens::BackboneResidue> trace = backbone.residues;
  for (auto& residue : trace)
    residue.has_n = residue.has_c = residue.has_o = false;
  const auto result = mesolens::assign_secondary_structure(trace);
  const std::string full =
    mesolens::dssp_string(mesolens::assign_secondary_structure(backbone.residues).structure);
  const std::string ours = mesolens::dssp_string(result.structure);
  std::size_t helix_agree = 0, helix_total = 0;
  for (std::size_t r = 0; r < full.size(); ++r)
  {
    EXPECT_EQ(result.from_ca_only[r], 1);
    if (full[r] == 'H')
    {
      ++helix_total;
      helix_agree += ours[r] == 'H';
    }
  }
  std::printf("1crn Cα only %s\n           full %s\n", ours.c_str(), full.c_str());
  EXPECT_GE(double(helix_agree) / double(helix_total), 0.8);
  EXPECT_NE(ours.find('E'), std::string::npos);
  // A Cα-only ideal helix.
  std::vector<std::array<double, 3>> ca;
  for (const auto& residue : ideal_backbone(16, -57.0, -47.0))
    ca.push_back(residue.ca);
  const std::string helix =
    mesolens::dssp_string(mesolens::assign_from_ca(ca, std::vector<int>(16, 0)));
  EXPECT_EQ(helix.substr(2, 12), std::string(12, 'H')) << helix;
}

TEST(Dssp, HysteresisWaitsForANewClassToHold)
{
  using S = SecondaryStructure;
  mesolens::SecondaryStructureHysteresis hold(3);
  EXPECT_EQ(hold.update({ S::Coil, S::AlphaHelix }), (std::vector<S>{ S::Coil, S::AlphaHelix }));
  EXPECT_EQ(hold.update({ S::Strand, S::AlphaHelix }), (std::vector<S>{ S::Coil, S::AlphaHelix }));
  EXPECT_EQ(hold.update({ S::Strand, S::Coil }), (std::vector<S>{ S::Coil, S::AlphaHelix }));
  EXPECT_EQ(hold.update({ S::Strand, S::AlphaHelix }),
            (std::vector<S>{ S::Strand, S::AlphaHelix }));
  // A flicker shorter than the hold never shows.
  for (int frame = 0; frame < 6; ++frame)
    EXPECT_EQ(hold.update({ S::Strand, frame % 2 ? S::Coil : S::AlphaHelix })[1], S::AlphaHelix);
  // One frame: no delay.
  mesolens::SecondaryStructureHysteresis none(1);
  none.update({ S::Coil });
  EXPECT_EQ(none.update({ S::Turn })[0], S::Turn);
  EXPECT_THROW(mesolens::SecondaryStructureHysteresis(0), mesolens::InvalidInput);
}

TEST(Dssp, BadInputs)
{
  EXPECT_TRUE(mesolens::assign_secondary_structure({}).structure.empty());
  auto one = ideal_backbone(1, -57.0, -47.0);
  EXPECT_EQ(mesolens::assign_secondary_structure(one).structure,
            std::vector<SecondaryStructure>{ SecondaryStructure::Coil });
  auto broken = ideal_backbone(10, -57.0, -47.0);
  broken[3].ca[1] = std::nan("");
  EXPECT_THROW(mesolens::assign_secondary_structure(broken), mesolens::InvalidInput);
  mesolens::DsspParams negative;
  negative.polyproline_stretch = -1;
  EXPECT_THROW(mesolens::assign_secondary_structure(ideal_backbone(5, -57.0, -47.0), negative),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::assign_from_ca(std::vector<std::array<double, 3>>{ { 0, 0, 0 } }, {}),
               mesolens::InvalidInput);
  // No residue with any backbone atom: all coil, nothing from Cα.
  std::vector<mesolens::BackboneResidue> empty_residues(4);
  const auto nothing = mesolens::assign_secondary_structure(empty_residues);
  EXPECT_EQ(nothing.structure, std::vector<SecondaryStructure>(4, SecondaryStructure::Coil));
  // A nucleic acid has no amino-acid residues.
  const auto dna = mesolens::read_structure(mesolens_test::data_file("proteins/1bna.pdb"));
  EXPECT_TRUE(mesolens::protein_backbone(dna.models[0]).residues.empty());
}

TEST(Dssp, NewFramesOfTheSameAtomsUpdateTheBackboneAndTheRibbonTrace)
{
  // Trp-cage's models are frames of the same atoms: model 0's backbone and trace take model 1's
  // positions and equal model 1's own.
  const auto file = mesolens::read_structure(mesolens_test::data_file("proteins/1l2y.pdb"));
  auto backbone = mesolens::protein_backbone(file.models[0]);
  const auto second = mesolens::protein_backbone(file.models[1]);
  backbone.update_positions(file.models[1].positions);
  ASSERT_EQ(backbone.residues.size(), second.residues.size());
  for (std::size_t r = 0; r < second.residues.size(); ++r)
  {
    EXPECT_EQ(backbone.residues[r].ca, second.residues[r].ca) << r;
    EXPECT_EQ(backbone.residues[r].o, second.residues[r].o) << r;
  }
  auto trace = mesolens::ribbon_trace(file.models[0]);
  trace.update(file.models[1].positions, nullptr);
  const auto second_trace = mesolens::ribbon_trace(file.models[1]);
  ASSERT_EQ(trace.residues.size(), second_trace.residues.size());
  EXPECT_EQ(trace.residues.back().trace, second_trace.residues.back().trace);
  // Positions that lack atoms the backbone or the trace uses are refused.
  const mesolens::PointSpan<const float> all = file.models[1].positions;
  const auto fewer = all.subspan(0, all.size() - 20);
  EXPECT_THROW(backbone.update_positions(fewer), mesolens::InvalidInput);
  EXPECT_THROW(trace.update(fewer, nullptr), mesolens::InvalidInput);
}
