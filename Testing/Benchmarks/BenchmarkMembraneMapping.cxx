// SPDX-License-Identifier: GPL-3.0-or-later
// Membrane-mapping benchmark and real-data report.
//  1. The full re-map on a ~2 M-triangle cell mesh (the mitochondrion's outer membrane, Loop-
//     subdivided 4 times): geodesic disk + parameterization + 225 polynomial fits for 15 x 15
//     tiles, step by step, with the ratio to CGAL's mean-value parameterization
//     (Surface_mesh_parameterization) of the same disk in the same run; then the CPU evaluation
//     of all mapped atoms for the paper's largest case (15 x 15 tiles of the 43 480-atom YiiP
//     patch, 9.8 M atoms). The goal is a re-map within 100 ms.
//  2. Real data: the DPPC and YiiP bilayers mapped onto the mitochondrion meshes at true scale
//     (Å onto µm), 3 x 3 tiles: median and 95th percentile bond-length change per method, and
//     the polynomial's fit residual per tile.
#include "mesolens/geodesic_disk.h"
#include "mesolens/gro_topology.h"
#include "mesolens/harmonic_parameterization.h"
#include "mesolens/membrane_mapping.h"
#include "mesolens/molecule_pbc.h"
#include "mesolens/trajectory_file.h"
#include "mesolens/structure_file.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkLoopSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <tuple>
#include <vector>

namespace {
using mesolens_test::median_seconds;
using mesolens_test::seconds_of;

mesolens::TriangleMesh to_mesh(vtkPolyData* surface)
{
  mesolens::TriangleMesh mesh;
  mesh.points.resize(3 * std::size_t(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    surface->GetPoint(i, mesh.points.data() + 3 * i);
  }
  auto cells = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(size, ids);
    mesh.triangles.insert(mesh.triangles.end(), { ids[0], ids[1], ids[2] });
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> read_obj(const std::string& path, int subdivisions)
{
  vtkNew<vtkOBJReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->ShallowCopy(reader->GetOutput());
  if (subdivisions > 0)
  {
    vtkNew<vtkLoopSubdivisionFilter> loop;
    loop->SetInputData(surface);
    loop->SetNumberOfSubdivisions(subdivisions);
    loop->Update();
    surface->ShallowCopy(loop->GetOutput());
  }
  return surface;
}

/// CGAL's mean-value parameterization of the same disk, with an arc-length circular border.
double cgal_parameterization_seconds(const mesolens::TriangleMesh& disk)
{
  using Kernel = CGAL::Simple_cartesian<double>;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  namespace SMP = CGAL::Surface_mesh_parameterization;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  for (std::size_t v = 0; v < disk.vertex_count(); ++v)
  {
    const auto p = disk.point(std::int64_t(v));
    vertices.push_back(mesh.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  }
  for (std::size_t t = 0; t < disk.triangle_count(); ++t)
  {
    mesh.add_face(vertices[std::size_t(disk.triangles[3 * t])],
                  vertices[std::size_t(disk.triangles[3 * t + 1])],
                  vertices[std::size_t(disk.triangles[3 * t + 2])]);
  }
  return median_seconds(3, [&] {
    auto uv = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
    const auto border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
    using Border = SMP::Circular_border_arc_length_parameterizer_3<Mesh>;
    using Parameterizer = SMP::Mean_value_coordinates_parameterizer_3<Mesh, Border>;
    const SMP::Error_code status = SMP::parameterize(mesh, Parameterizer(), border, uv);
    if (status != SMP::OK)
    {
      std::printf("CGAL parameterization failed: %s\n", SMP::get_error_message(status));
    }
    mesh.remove_property_map(uv);
  });
}

/// A patch view of a GRO membrane, with its own storage.
struct Membrane
{
  mesolens::AtomTable table;
  std::vector<float> masses;
  std::vector<std::array<std::uint32_t, 2>> bonds;
  mesolens::MembranePatch patch() const
  {
    mesolens::MembranePatch p;
    p.positions = this->table.positions.data();
    p.atom_count = this->table.size();
    p.molecule_ids = this->table.molecule_ids.data();
    p.masses = this->masses.data();
    p.a = { this->table.box.vectors[0][0], this->table.box.vectors[0][1] };
    p.b = { this->table.box.vectors[1][0], this->table.box.vectors[1][1] };
    double height = 0;
    for (std::size_t i = 0; i < this->table.size(); ++i)
    {
      height += this->table.positions[3 * i + 2] / double(this->table.size());
    }
    p.centre_height = height;
    return p;
  }
  double width() const
  {
    return std::max(std::hypot(this->table.box.vectors[0][0], this->table.box.vectors[0][1]),
                    std::hypot(this->table.box.vectors[1][0], this->table.box.vectors[1][1]));
  }
};

Membrane read_membrane(const std::string& gro)
{
  Membrane m;
  m.table = mesolens::read_gro_topology(gro);
  mesolens::StructureReadParams params;
  mesolens::build_connectivity(m.table, {}, params, false);
  std::vector<bool> keep(m.table.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
  {
    keep[i] = !mesolens::is_water_residue(m.table.residue_names[i]);
  }
  m.table.filter(keep);
  for (std::size_t i = 0; i < m.table.size(); ++i)
  {
    m.masses.push_back(1.0f);
  }
  for (const mesolens::Bond& b : m.table.bonds)
  {
    m.bonds.push_back({ b.first, b.second });
  }
  return m;
}

void real_data_report(const std::string& mesh_name, const std::string& mesh_path,
                      const std::string& membrane_name, const Membrane& membrane)
{
  const auto surface = read_obj(mesh_path, 0);
  const mesolens::CellSurface solver(to_mesh(surface));
  const auto seed = solver.closest_point(solver.mesh().point(1000));
  const double scale = 1e-4; // Å onto µm
  const int tiles = 3;
  const double radius = 2 * tiles * membrane.width() * scale;
  mesolens::GeodesicDiskParams disk_params;
  disk_params.radius = radius;
  const auto disk = mesolens::geodesic_disk(solver, seed, disk_params);
  const auto map = mesolens::harmonic_parameterization(disk.mesh, radius);
  const mesolens::SurfaceChart chart(disk.mesh, map.uv);
  for (const auto method :
       { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
         mesolens::MappingMethod::Polynomial })
  {
    mesolens::MappingParams params;
    params.method = method;
    params.tiles = tiles;
    params.scale = scale;
    params.centre_uv = chart.uv_of(disk.seed);
    const auto patch = membrane.patch();
    const auto mapped = mesolens::map_membrane(chart, patch, params);
    auto changes = mesolens::bond_length_changes(patch, mapped, membrane.bonds, scale);
    for (double& c : changes)
    {
      c = std::abs(c);
    }
    std::sort(changes.begin(), changes.end());
    const char* names[] = { "displacement", "instancing", "polynomial" };
    std::printf("REPORT mapping membrane=%s mesh=%s tiles=3x3 disk=%zu triangles (refinement %d) "
                "method=%s | |bond length change| median %.2e, 95th percentile %.2e, max %.2e",
                membrane_name.c_str(), mesh_name.c_str(), disk.mesh.triangle_count(),
                disk.refinement_levels, names[int(method)], changes[changes.size() / 2],
                changes[changes.size() * 95 / 100], changes.back());
    if (method == mesolens::MappingMethod::Polynomial)
    {
      auto residual = mapped.polynomial_rms_residual;
      std::sort(residual.begin(), residual.end());
      std::printf(" | fit residual RMS per tile: median %.3f Å, max %.3f Å (max point %.3f Å)",
                  residual[residual.size() / 2] / scale, residual.back() / scale,
                  *std::max_element(mapped.polynomial_max_residual.begin(),
                                    mapped.polynomial_max_residual.end()) /
                    scale);
    }
    std::printf("\n");
  }
}
/// The YiiP trajectory, frame by frame, mapped by displacement (the disk is grown once).
void trajectory_report(const std::string& mesh_path, const std::string& gro, const std::string& xtc)
{
  Membrane membrane;
  membrane.table = mesolens::read_gro_topology(gro);
  mesolens::build_connectivity(membrane.table, {}, mesolens::StructureReadParams{}, false);
  membrane.masses.assign(membrane.table.size(), 1.0f);
  for (const mesolens::Bond& b : membrane.table.bonds)
  {
    membrane.bonds.push_back({ b.first, b.second });
  }
  const mesolens::CellSurface solver(to_mesh(read_obj(mesh_path, 0)));
  const auto seed = solver.closest_point(solver.mesh().point(1000));
  const double scale = 1e-4;
  const double radius = 2 * 3 * membrane.width() * scale;
  mesolens::GeodesicDiskParams disk_params;
  disk_params.radius = radius;
  const auto disk = mesolens::geodesic_disk(solver, seed, disk_params);
  const mesolens::SurfaceChart chart(disk.mesh,
                                     mesolens::harmonic_parameterization(disk.mesh, radius).uv);
  mesolens::TrajectoryFile frames(xtc);
  for (std::size_t f = 0; f < frames.frame_count(); ++f)
  {
    mesolens::TrajectoryFrame frame = frames.read_frame(f);
    mesolens::make_molecules_whole(frame.positions.data(), membrane.table.molecule_ids.data(),
                                   membrane.table.size(), frame.box);
    membrane.table.positions = frame.positions;
    membrane.table.box = frame.box;
    mesolens::MappingParams params;
    params.tiles = 3;
    params.scale = scale;
    params.centre_uv = chart.uv_of(disk.seed);
    const auto patch = membrane.patch();
    const double seconds = seconds_of([&] { mesolens::map_membrane(chart, patch, params); });
    const auto mapped = mesolens::map_membrane(chart, patch, params);
    auto changes = mesolens::bond_length_changes(patch, mapped, membrane.bonds, scale);
    for (double& c : changes)
    {
      c = std::abs(c);
    }
    std::sort(changes.begin(), changes.end());
    std::printf(
      "REPORT trajectory membrane=YiiP POPE/POPG + protein (%zu atoms) frame=%zu (%.0f ns) "
      "mesh=mito5_outer_membrane tiles=3x3 method=displacement | re-map of the frame %.1f ms | "
      "|bond length change| median %.2e, 95th percentile %.2e\n",
      membrane.table.size(), f, frame.time_ps / 1000, 1e3 * seconds, changes[changes.size() / 2],
      changes[changes.size() * 95 / 100]);
  }
}
} // namespace

int main()
{
  using mesolens_test::data_file;
  const Membrane yiip = read_membrane(data_file("membranes/yiip_popepopg.gro"));
  const Membrane dppc = read_membrane(data_file("membranes/dppc128_slipids_323K.gro"));

  // 1. The re-map on ~2 M triangles.
  vtkSmartPointer<vtkPolyData> surface;
  const double subdivide =
    seconds_of([&] { surface = read_obj(data_file("meshes/mito5_outer_membrane.obj"), 4); });
  mesolens::TriangleMesh mesh = to_mesh(surface);
  const std::size_t triangles = mesh.triangle_count();
  std::unique_ptr<mesolens::CellSurface> solver;
  const double setup =
    seconds_of([&] { solver = std::make_unique<mesolens::CellSurface>(std::move(mesh)); });
  std::printf(
    "BENCH remap-setup input=mito5_outer_membrane Loop x4 = %zu triangles | subdivision %.2f s, "
    "solver set-up (once per mesh) %.2f s\n",
    triangles, subdivide, setup);
  const int tiles = 15;
  // The 15 x 15 YiiP tiling (1545 Å wide) does not fit this 0.6 µm organelle at true scale:
  // shrink it so the disk (r = 2 d) has a radius of 0.12 µm.
  const double radius = 0.12;
  const double scale = radius / (2 * tiles * yiip.width());
  const auto seed = solver->closest_point(solver->mesh().point(1000));
  mesolens::GeodesicDiskParams disk_params;
  disk_params.radius = radius;
  disk_params.min_triangles = 0;
  mesolens::GeodesicDisk disk;
  const double geodesic =
    median_seconds(3, [&] { disk = mesolens::geodesic_disk(*solver, seed, disk_params); });
  mesolens::DiskParameterization map;
  const double parameterization =
    median_seconds(3, [&] { map = mesolens::harmonic_parameterization(disk.mesh, radius); });
  std::unique_ptr<mesolens::SurfaceChart> chart;
  const double chart_build =
    median_seconds(3, [&] { chart = std::make_unique<mesolens::SurfaceChart>(disk.mesh, map.uv); });
  mesolens::MappingParams params;
  params.method = mesolens::MappingMethod::Polynomial;
  params.tiles = tiles;
  params.scale = scale;
  params.centre_uv = chart->uv_of(disk.seed);
  auto one_atom = yiip.patch();
  one_atom.atom_count = 1;
  const double fits = median_seconds(3, [&] { mesolens::map_membrane(*chart, one_atom, params); });
  const double remap = geodesic + parameterization + chart_build + fits;
  const double cgal = cgal_parameterization_seconds(disk.mesh);
  std::printf("BENCH remap input=%zu-triangle mesh, disk of %zu triangles, 15x15 tiles of YiiP "
              "(scale %.2e µm/Å) | "
              "geodesic disk %.1f ms + parameterization %.1f ms + chart %.1f ms + 225 polynomial "
              "fits %.1f ms = "
              "re-map %.1f ms (goal 100 ms) | CGAL mean-value parameterization %.1f ms | ratio "
              "ours/CGAL %.2f\n",
              triangles, disk.mesh.triangle_count(), scale, 1e3 * geodesic, 1e3 * parameterization,
              1e3 * chart_build, 1e3 * fits, 1e3 * remap, 1e3 * cgal, parameterization / cgal);
  const auto patch = yiip.patch();
  mesolens::MappedMembrane mapped;
  const double evaluation =
    median_seconds(1, [&] { mapped = mesolens::map_membrane(*chart, patch, params); }) - fits;
  const double atoms = double(mapped.positions.size() / 3);
  std::printf("BENCH cpu-evaluation input=15x15 tiles x %zu atoms = %.0f atoms (polynomial) | %.0f "
              "ms, %.1f Matoms/s "
              "(single thread)\n",
              patch.atom_count, atoms, 1e3 * evaluation, atoms / evaluation / 1e6);
  solver.reset();

  // The interactive case: the organelle mesh as it comes (8340 triangles), the disk refined
  // locally (Loop subdivision) until it holds 2000 triangles.
  const mesolens::CellSurface coarse(
    to_mesh(read_obj(data_file("meshes/mito5_outer_membrane.obj"), 0)));
  const auto coarse_seed = coarse.closest_point(coarse.mesh().point(1000));
  for (const auto& [label, k, factor] :
       { std::make_tuple("15x15 tiles (scale as above)", 15, scale),
         std::make_tuple("3x3 tiles at true scale (1e-4 µm/Å)", 3, 1e-4) })
  {
    mesolens::GeodesicDiskParams local;
    local.radius = 2 * k * yiip.width() * factor;
    mesolens::GeodesicDisk small;
    const double grow =
      median_seconds(5, [&] { small = mesolens::geodesic_disk(coarse, coarse_seed, local); });
    mesolens::DiskParameterization small_map;
    const double flatten = median_seconds(
      5, [&] { small_map = mesolens::harmonic_parameterization(small.mesh, local.radius); });
    std::unique_ptr<mesolens::SurfaceChart> small_chart;
    const double index = median_seconds(
      5, [&] { small_chart = std::make_unique<mesolens::SurfaceChart>(small.mesh, small_map.uv); });
    mesolens::MappingParams fit_params = params;
    fit_params.tiles = k;
    fit_params.scale = factor;
    fit_params.centre_uv = small_chart->uv_of(small.seed);
    const double fit =
      median_seconds(5, [&] { mesolens::map_membrane(*small_chart, one_atom, fit_params); });
    std::printf(
      "BENCH remap-interactive input=mito5_outer_membrane (8340 triangles), YiiP %s, disk of %zu "
      "triangles after %d Loop levels | geodesic disk %.1f ms + parameterization %.1f ms + chart "
      "%.1f ms "
      "+ %d polynomial fits %.1f ms = re-map %.1f ms (goal 100 ms)\n",
      label, small.mesh.triangle_count(), small.refinement_levels, 1e3 * grow, 1e3 * flatten,
      1e3 * index, k * k, 1e3 * fit, 1e3 * (grow + flatten + index + fit));
  }

  // 2. Real data at true scale.
  real_data_report("mito5_outer_membrane", data_file("meshes/mito5_outer_membrane.obj"),
                   "DPPC (Slipids)", dppc);
  real_data_report("mito5_outer_membrane", data_file("meshes/mito5_outer_membrane.obj"),
                   "YiiP POPE/POPG", yiip);
  trajectory_report(data_file("meshes/mito5_outer_membrane.obj"),
                    data_file("membranes/yiip_popepopg.gro"),
                    data_file("membranes/yiip_popepopg.xtc"));
  const std::string inner = mesolens_test::shared_file("meshes/mito5_inner_membrane.obj");
  if (mesolens_test::exists(inner))
  {
    real_data_report("mito5_inner_membrane", inner, "DPPC (Slipids)", dppc);
    real_data_report("mito5_inner_membrane", inner, "YiiP POPE/POPG", yiip);
  }
  else
  {
    std::printf("REPORT skipped the inner membrane: %s not found\n", inner.c_str());
  }
  return 0;
}
