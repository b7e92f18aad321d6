// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: DSSP (mesolens::assign_secondary_structure) and the ribbon sweep
// (mesolens::ribbon_mesh) on arbitrary backbones: missing atoms, broken and one-residue chains,
// coincident and far-apart residues, Cα-only chains, nucleotides among amino acids, every
// secondary-structure code and ribbon setting at and past its limits. Every input must give an
// assignment and a closed, consistently oriented mesh of finite points, or a mesolens::Error.
//
// Input: a byte of DSSP options, bytes of ribbon settings, then per residue (at most 48) a byte
// saying which atoms it has and how it follows the last one, and its numbers.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/protein/dssp.h"
#include "mesolens/protein/protein_backbone.h"
#include "mesolens/protein/ribbon_geometry.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

using mesolens_fuzz::require;

std::array<double, 3> near(mesolens_fuzz::FuzzInput& input, const std::array<double, 3>& origin,
                           double reach)
{
  return { origin[0] + input.ranged(-reach, reach), origin[1] + input.ranged(-reach, reach),
           origin[2] + input.ranged(-reach, reach) };
}

std::vector<mesolens::BackboneResidue> backbone(mesolens_fuzz::FuzzInput& input,
                                                std::vector<std::uint8_t>& nucleotide)
{
  std::vector<mesolens::BackboneResidue> residues;
  std::array<double, 3> last{};
  int chain = 0;
  const std::size_t count = input.byte() % 49;
  for (std::size_t i = 0; i < count && !input.empty(); ++i)
  {
    const std::uint8_t how = input.byte();
    mesolens::BackboneResidue r;
    r.has_n = !(how & 1);
    r.has_ca = !(how & 2) || (how & 0xc0) == 0xc0;
    r.has_c = !(how & 4);
    r.has_o = !(how & 8);
    r.proline = how & 16;
    if (how & 32)
    {
      ++chain;
    }
    r.chain = chain;
    const std::uint8_t step = (how >> 6) & 3;
    // A peptide step (3.8 Å), a step onto the last residue, or a jump.
    r.ca = step == 1 ? last : near(input, last, step == 2 ? 40.0 : 3.8);
    r.n = near(input, r.ca, 1.5);
    r.c = near(input, r.ca, 1.5);
    r.o = near(input, r.c, 1.3);
    const std::uint8_t extra = input.byte();
    r.has_h = extra & 1;
    r.h = near(input, r.n, 1.0);
    nucleotide.push_back((extra & 6) == 6);
    last = r.ca;
    residues.push_back(r);
  }
  return residues;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t dssp_byte = input.byte();
  mesolens::DsspParams dssp;
  dssp.pi_helix_priority = dssp_byte & 1;
  dssp.bulges = dssp_byte & 2;
  dssp.file_hydrogens = dssp_byte & 4;
  dssp.polyproline_stretch = int(dssp_byte >> 3) - 2; // -2 is out of range
  mesolens::RibbonParams ribbon;
  const std::uint8_t ribbon_byte = input.byte();
  ribbon.subdivisions = int(input.byte() % 14) - 1;
  ribbon.tube_sides = int(input.byte() % 19) + 1;
  ribbon.helix_as_cylinder = ribbon_byte & 1;
  if (ribbon_byte & 2)
  {
    ribbon.helix_width = input.ranged(0.0, 5.0);
    ribbon.ribbon_thickness = input.ranged(0.0, 2.0);
    ribbon.coil_radius = input.ranged(0.0, 1.0);
    ribbon.arrow_width_factor = input.ranged(0.5, 3.0);
    ribbon.protein_break_distance = input.ranged(0.0, 8.0);
  }
  std::vector<std::uint8_t> nucleotide;
  const std::vector<mesolens::BackboneResidue> residues = backbone(input, nucleotide);

  std::vector<mesolens::SecondaryStructure> structure(residues.size(),
                                                      mesolens::SecondaryStructure::Coil);
  try
  {
    const mesolens::DsspResult result = mesolens::assign_secondary_structure(residues, dssp);
    require(result.structure.size() == residues.size());
    require(result.break_before.size() == residues.size());
    require(result.from_ca_only.size() == residues.size());
    structure = result.structure;
  }
  catch (const mesolens::Error&)
  {
  }

  std::vector<mesolens::RibbonResidue> ribbon_residues;
  for (std::size_t i = 0; i < residues.size(); ++i)
  {
    if (!residues[i].has_ca)
    {
      continue; // as the ribbon filter leaves residues without a trace atom out
    }
    mesolens::RibbonResidue r;
    r.trace = residues[i].ca;
    if (residues[i].has_o && !nucleotide[i])
    {
      r.carbonyl_oxygen = residues[i].o;
    }
    r.secondary_structure = mesolens::dssp_letter(structure[i]);
    r.nucleotide = nucleotide[i];
    r.chain = residues[i].chain;
    r.id = std::int64_t(i);
    ribbon_residues.push_back(r);
  }
  try
  {
    const mesolens::RibbonMesh mesh = mesolens::ribbon_mesh(ribbon_residues, ribbon);
    for (const double x : mesh.points)
    {
      require(std::isfinite(x));
    }
    require(mesh.normals.size() == mesh.points.size());
    for (std::size_t v = 0; v < mesh.normals.size(); v += 3)
    {
      const double length = std::hypot(mesh.normals[v], mesh.normals[v + 1], mesh.normals[v + 2]);
      require(std::abs(length - 1) < 1e-6);
    }
    require(mesh.vertex_residue_id.size() == mesh.vertex_count());
    require(mesh.vertex_secondary_structure.size() == mesh.vertex_count());
    mesolens_fuzz::require_closed_mesh(mesh.vertex_count(), mesh.triangles);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
