// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the structure mesh (mesolens::structure_mesh) of arbitrary molecule clouds,
// with every setting at and past its limits. Every input must give one connected 2-manifold or
// a mesolens::Error. The input's layout is that of fuzz_cutaway's structure-mesh inputs before
// the two were split, so the seeds of either replay here.
#include "fuzz_input.h"
#include "fuzz_molecule_cloud.h"

#include "mesolens/common/errors.h"
#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/mesh/mesh_report.h"

#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  const std::vector<double> centres = mesolens_fuzz::molecule_cloud(input);
  mesolens::StructureMeshParams params;
  params.vertices = std::size_t(input.byte()) * 3;
  params.edge_length = (options & 8) ? input.ranged(-1, 30) : 0;
  params.mid_surface_radius = (options & 16) ? input.ranged(-1, 60) : 0;
  // Meshes past this limit are refused (counts asked here reach 765, so both ways are tried):
  // the angle repair of a poor first mesh takes about 1.5 ms per vertex, ten times that under
  // the sanitizers, and 800 vertices overran the 10 s timeout.
  params.vertex_limit = 400;
  try
  {
    const mesolens::TriangleMesh structure = mesolens::structure_mesh(centres, params);
    const mesolens::MeshReport report = mesolens::mesh_report(structure.view());
    mesolens_fuzz::require(report.is_manifold() && report.components == 1);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
