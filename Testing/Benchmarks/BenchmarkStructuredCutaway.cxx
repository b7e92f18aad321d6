// SPDX-License-Identifier: GPL-3.0-or-later
// Structured-cutaway benchmark: an HIV-envelope-sized vesicle (a sphere of 150 nm diameter)
// covered by the Martini DPPC/cholesterol bilayer from Data/, mapped tile by tile with
// vtkMesoMembraneMapping (about 240 000 lipids, 2.7 M beads). Timed, each as the median of a few
// runs: the full preparation (molecule centres, structure mesh from the centres, assignment of
// every lipid to its nearest triangle, priorities, removal order and mask) at the thesis' 50 and
// 150 vertices and at 500; then a slider update (a new fraction hidden: the mask of 2.7 M atoms)
// through the filter and in Core alone. Baselines: the SirTom thesis' preprocessing of 220 000
// lipids of an HIV membrane, 14.5 s with 50 vertices and 41 s with 150 (MeshLab mesh by hand
// not counted); goals: preparation <= 0.5 s, slider <= 5 ms.
//
//   BenchmarkStructuredCutaway [--seeds N] [--repeats N]
#include "vtkMesoArrayNames.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/cutaway/surface_sampling.h"
#include "mesolens/cutaway/structured_cutaway.h"

#include <vtkAppendPolyData.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {
using mesolens_test::median_seconds;
using mesolens_test::seconds_of;

constexpr double vesicle_radius = 750.0; // Å: 150 nm across, an HIV envelope

/// The bilayer mapped around `seeds` points spread evenly (Fibonacci) over the vesicle, 3 x 3
/// tiles each; molecule ids made unique over the copies.
vtkSmartPointer<vtkPolyData> hiv_sized_vesicle(int seeds)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(vesicle_radius);
  sphere->SetThetaResolution(180);
  sphere->SetPhiResolution(180);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(sphere->GetOutputPort());
  triangles->Update();
  vtkNew<vtkMesoTrajectoryReader> bilayer;
  bilayer->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  bilayer->Update();
  vtkNew<vtkAppendPolyData> append;
  const double golden = 3.14159265358979 * (3 - std::sqrt(5.0));
  int first_id = 0;
  for (int s = 0; s < seeds; ++s)
  {
    const double z = 1 - 2 * (s + 0.5) / seeds;
    const double r = std::sqrt(1 - z * z);
    vtkNew<vtkMesoMembraneMapping> mapping;
    mapping->SetInputData(0, triangles->GetOutput());
    mapping->SetMembraneConnection(bilayer->GetOutputPort());
    mapping->SetMappingMethodToMoleculeInstancing();
    mapping->SetTiles(3);
    mapping->SetRadiusFactor(1.0);
    mapping->SetSeedPoint(vesicle_radius * r * std::cos(golden * s),
                          vesicle_radius * r * std::sin(golden * s), vesicle_radius * z);
    mapping->Update();
    vtkNew<vtkPolyData> mapped;
    mapped->ShallowCopy(mapping->GetOutput());
    if (mapped->GetNumberOfPoints() == 0)
    {
      continue;
    }
    // The mapping numbers its tiles' molecules apart; the mappings are numbered apart here.
    vtkDataArray* ids = mapped->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    vtkNew<vtkIntArray> unique;
    unique->SetName(vtkMesoArrayNames::MoleculeId);
    unique->SetNumberOfValues(mapped->GetNumberOfPoints());
    for (vtkIdType a = 0; a < mapped->GetNumberOfPoints(); ++a)
    {
      unique->SetValue(a, first_id + int(ids->GetTuple1(a)));
    }
    first_id += int(ids->GetRange()[1]) + 1;
    mapped->GetPointData()->AddArray(unique);
    mapped->GetFieldData()->Initialize(); // no periodic box: the vesicle is whole
    append->AddInputData(mapped);
  }
  append->Update();
  vtkSmartPointer<vtkPolyData> vesicle = append->GetOutput();
  return vesicle;
}
} // namespace

int main(int argc, char* argv[])
{
  const int seeds = mesolens_test::count_argument(argc, argv, "--seeds", 60);
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", 3);
  vtkSmartPointer<vtkPolyData> vesicle;
  const double build = seconds_of([&] { vesicle = hiv_sized_vesicle(seeds); });
  vtkDataArray* ids = vesicle->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  const long lipids = long(ids->GetRange()[1]) + 1;
  std::printf("BENCH structured-cutaway input: vesicle of radius %.0f Å, %d mapped 3x3 tiles of "
              "the Martini DPPC/CHOL "
              "bilayer: %lld beads, up to %ld lipids (built in %.1f s); %d threads\n",
              vesicle_radius, seeds, static_cast<long long>(vesicle->GetNumberOfPoints()), lipids,
              build, vtkMesoParallelFor::ThreadCount());

  vtkNew<vtkPlane> plane; // the half facing +x is cut
  plane->SetOrigin(0, 0, 0);
  plane->SetNormal(-1, 0, 0);
  const double thesis_seconds[2] = { 14.5, 41.0 };
  for (int vertices : { 50, 150, 500 })
  {
    long molecules = 0;
    long in_cut = 0;
    double min_angle = 0;
    const double prepare = median_seconds(repeats, [&] {
      vtkNew<vtkMesoStructuredCutaway> cutaway;
      cutaway->SetInputData(vesicle);
      cutaway->SetStructureVertices(vertices);
      cutaway->SetCutFunction(plane);
      cutaway->SetFractionHidden(0.5);
      cutaway->Update();
      molecules = long(cutaway->GetOutput()
                         ->GetFieldData()
                         ->GetArray(vtkMesoArrayNames::MoleculeVisible)
                         ->GetNumberOfTuples());
      in_cut = long(cutaway->GetOutput()
                      ->GetFieldData()
                      ->GetArray(vtkMesoArrayNames::MoleculesInCut)
                      ->GetTuple1(0));
      min_angle =
        cutaway->GetOutput(1)->GetFieldData()->GetArray(vtkMesoArrayNames::MinAngle)->GetTuple1(0);
    });
    std::printf("BENCH structured-cutaway preparation, %d structure vertices: %ld lipids (%ld in "
                "the cut), %.3f s "
                "(min angle %.1f°)",
                vertices, molecules, in_cut, prepare, min_angle);
    if (vertices <= 150)
    {
      const double thesis = thesis_seconds[vertices == 50 ? 0 : 1];
      std::printf("; thesis %.1f s for 220k lipids, ratio %.4f", thesis, prepare / thesis);
    }
    std::printf("; goal <= 0.5 s\n");
  }

  // Step by step in Core at 150 vertices, from the molecules' centres.
  {
    std::vector<double> centres(3 * std::size_t(lipids), 0.0);
    std::vector<double> counts(std::size_t(lipids), 0.0);
    std::vector<int> molecule_of(std::size_t(vesicle->GetNumberOfPoints()));
    const double centring = seconds_of([&] {
      for (vtkIdType a = 0; a < vesicle->GetNumberOfPoints(); ++a)
      {
        const int m = int(ids->GetTuple1(a));
        double p[3];
        vesicle->GetPoint(a, p);
        for (int d = 0; d < 3; ++d)
          centres[3 * std::size_t(m) + d] += p[d];
        counts[std::size_t(m)] += 1;
      }
    });
    std::vector<double> present;
    for (std::size_t m = 0; m < counts.size(); ++m)
      if (counts[m] > 0)
        for (int d = 0; d < 3; ++d)
          present.push_back(centres[3 * m + d] / counts[m]);
    const mesolens::ParallelFor parallel = [](std::size_t count,
                                              const mesolens::RangeKernel& kernel) {
      vtkSMPTools::For(0, vtkIdType(count),
                       [&](vtkIdType b, vtkIdType e) { kernel(std::size_t(b), std::size_t(e)); });
    };
    double spacing = 0;
    const double spacing_time =
      median_seconds(repeats, [&] { spacing = mesolens::median_spacing(present); });
    mesolens::TriangleMesh mesh;
    const double mesh_time = median_seconds(repeats, [&] {
      mesh = mesolens::structure_mesh(present, { 150, 0, 0 }, nullptr, parallel);
    });
    std::unique_ptr<mesolens::StructuredCutaway> solver;
    const double assign_time = median_seconds(repeats, [&] {
      solver =
        std::make_unique<mesolens::StructuredCutaway>(mesh, present, std::vector<int>{}, parallel);
    });
    mesolens::CutawayParams settings;
    const auto half = [](const std::array<double, 3>& p) { return p[0] >= 0; };
    mesolens::RemovalOrder order;
    const double order_time =
      median_seconds(repeats, [&] { order = solver->removal_order(half, settings); });
    const double mask_time = median_seconds(21, [&] {
      settings.fraction_hidden =
        settings.fraction_hidden > 0.8 ? 0.1 : settings.fraction_hidden + 0.05;
      (void)solver->visibility(order, settings);
    });
    std::printf("BENCH structured-cutaway core, 150 vertices, %zu lipid centres (median spacing "
                "%.1f Å, in %.3f s): "
                "centres from atoms %.3f s; structure mesh %.3f s (%zu vertices); assignment "
                "%.3f s; removal order %.1f ms; mask for a new fraction %.2f ms\n",
                present.size() / 3, spacing, spacing_time, centring, mesh_time, mesh.vertex_count(),
                assign_time, 1e3 * order_time, 1e3 * mask_time);
  }

  // A slider and a moving cut plane at 150 vertices.
  {
    vtkNew<vtkMesoStructuredCutaway> cutaway;
    cutaway->SetInputData(vesicle);
    cutaway->SetStructureVertices(150);
    cutaway->SetCutFunction(plane);
    cutaway->SetFractionHidden(0.5);
    const double first = seconds_of([&] { cutaway->Update(); });
    const int orderings = cutaway->GetNumberOfOrderings();
    double fraction = 0.1;
    const double slider = median_seconds(21, [&] {
      fraction = fraction > 0.85 ? 0.1 : fraction + 0.04;
      cutaway->SetFractionHidden(fraction);
      cutaway->Update();
    });
    const int slider_orderings = cutaway->GetNumberOfOrderings() - orderings;
    const double plane_move = median_seconds(5, [&] {
      plane->SetOrigin(fraction * 100, 0, 0);
      fraction = fraction > 0.85 ? 0.1 : fraction + 0.04;
      cutaway->Update();
    });
    std::printf("BENCH structured-cutaway filter, 150 vertices: first update %.3f s; slider update "
                "(new fraction, mask of "
                "%lld atoms) %.2f ms, goal <= 5 ms, ratio to goal %.2f; orderings during the "
                "slider %d; moving the cut plane (new order) %.1f ms; assignments %d\n",
                first, static_cast<long long>(vesicle->GetNumberOfPoints()), 1e3 * slider,
                1e3 * slider / 5.0, slider_orderings, 1e3 * plane_move,
                cutaway->GetNumberOfAssignments());
  }
  return 0;
}
