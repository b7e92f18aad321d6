// SPDX-License-Identifier: GPL-3.0-or-later
// Membrane-mapping benchmark and real-data report.
//  1. The full re-map on a ~2 M-triangle cell mesh (the mitochondrion's outer membrane, Loop-
//     subdivided 4 times) through mesolens::MembraneMapper, as a click does: geodesic disk +
//     parameterization + chart + 225 polynomial fits for 15 x 15 tiles of YiiP, on 2 threads,
//     the median of several clicks with nothing cached, and step by step; the ratio to CGAL's
//     mean-value parameterization (Surface_mesh_parameterization) of the same disk in the same
//     run; and what growing the disk on a coarser copy of the mesh changes against the
//     full-resolution solve (angle and area distortion, bond-length change). Then the CPU
//     evaluation of all mapped atoms for the paper's largest case (9.8 M atoms). Goal: a re-map
//     within 100 ms.
//  2. Real data: the DPPC and YiiP bilayers mapped onto the mitochondrion meshes at true scale
//     (Å onto µm), 3 x 3 tiles: median and 95th percentile bond-length change per method, and
//     the polynomial's fit residual per tile.
//
//   BenchmarkMembraneMapping [--smoke]   (--smoke: the re-map only, without the comparisons)
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/molecules/molecule_pbc.h"
#include "mesolens/io/trajectory_file.h"
#include "mesolens/io/structure_file.h"
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
#include <string>
#include <thread>
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
    p.positions = this->table.positions;
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
  const mesolens::MembraneMapper mapper(to_mesh(read_obj(mesh_path, 0)));
  const auto seed = mapper.seed_near(mapper.surface().mesh().point(1000));
  const double scale = 1e-4; // Å onto µm
  const int tiles = 3;
  const double radius = 2 * tiles * membrane.width() * scale;
  const auto mapping_chart = mapper.chart(seed, radius);
  const mesolens::GeodesicDisk& disk = mapping_chart->disk;
  const mesolens::SurfaceChart& chart = mapping_chart->chart;
  for (const auto method :
       { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
         mesolens::MappingMethod::Polynomial })
  {
    mesolens::MappingParams params;
    params.method = method;
    params.tiles = tiles;
    params.scale = scale;
    params.centre_uv = mapping_chart->seed_uv;
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
  const mesolens::MembraneMapper mapper(to_mesh(read_obj(mesh_path, 0)));
  const auto seed = mapper.seed_near(mapper.surface().mesh().point(1000));
  const double scale = 1e-4;
  const double radius = 2 * 3 * membrane.width() * scale;
  const auto mapping_chart = mapper.chart(seed, radius);
  const mesolens::SurfaceChart& chart = mapping_chart->chart;
  mesolens::TrajectoryFile frames(xtc);
  for (std::size_t f = 0; f < frames.frame_count(); ++f)
  {
    mesolens::TrajectoryFrame frame = frames.read_frame(f);
    mesolens::make_molecules_whole(frame.positions, membrane.table.molecule_ids.data(), frame.box);
    membrane.table.positions = frame.positions;
    membrane.table.box = frame.box;
    mesolens::MappingParams params;
    params.tiles = 3;
    params.scale = scale;
    params.centre_uv = mapping_chart->seed_uv;
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
/// How the polynomial's tiles were split: "1 x 1" or, say, "1-4 x 1-4 (3 of 225 tiles split)".
std::string pieces_of(const mesolens::MappedMembrane& mapped)
{
  const auto& m = mapped.polynomial_splits;
  if (m.empty())
  {
    return "no";
  }
  const int low = *std::min_element(m.begin(), m.end());
  const int high = *std::max_element(m.begin(), m.end());
  const auto split = std::count_if(m.begin(), m.end(), [](int s) { return s > 1; });
  if (low == high)
  {
    return std::to_string(low) + " x " + std::to_string(low);
  }
  return std::to_string(low) + "-" + std::to_string(high) + " x " + std::to_string(low) + "-" +
    std::to_string(high) + " (" + std::to_string(split) + " of " + std::to_string(m.size()) +
    " tiles split)";
}

/// Percentiles of a sample (sorted copy): p in [0, 1].
double percentile(std::vector<double> values, double p)
{
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, std::size_t(p * double(values.size())))];
}

std::vector<double> absolute(std::vector<double> values)
{
  for (double& v : values)
  {
    v = std::abs(v);
  }
  return values;
}

/// |log| of each area distortion: 0 where areas are kept, symmetric in shrinking and growing.
std::vector<double> log_area(const std::vector<double>& values)
{
  std::vector<double> out;
  for (const double v : values)
  {
    out.push_back(std::abs(std::log(v)));
  }
  return out;
}

mesolens::ParallelFor two_threads()
{
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    std::thread other([&] { kernel(0, count / 2); });
    kernel(count / 2, count);
    other.join();
  };
}

/// The re-map on ~2 M triangles.
void remap_on_two_million(const Membrane& yiip, bool smoke)
{
  using mesolens_test::data_file;
  vtkSmartPointer<vtkPolyData> surface;
  const double subdivide =
    seconds_of([&] { surface = read_obj(data_file("meshes/mito5_outer_membrane.obj"), 4); });
  mesolens::TriangleMesh mesh = to_mesh(surface);
  const std::size_t triangles = mesh.triangle_count();
  std::unique_ptr<mesolens::MembraneMapper> mapper;
  const double setup =
    seconds_of([&] { mapper = std::make_unique<mesolens::MembraneMapper>(std::move(mesh)); });
  std::printf(
    "BENCH remap-setup input=mito5_outer_membrane Loop x4 = %zu triangles | subdivision %.2f s, "
    "mapper set-up (once per mesh: checks, adjacency, %zu coarser copies) %.2f s\n",
    triangles, subdivide, mapper->surface().level_count() - 1, setup);
  const int tiles = 15;
  // The 15 x 15 YiiP tiling (1545 Å wide) does not fit this 0.6 µm organelle at true scale:
  // shrink it so the disk (r = 2 d) has a radius of 0.12 µm.
  const double radius = 0.12;
  const double scale = radius / (2 * tiles * yiip.width());
  const auto patch = yiip.patch();
  mesolens::MapRequest request;
  request.mapping.method = mesolens::MappingMethod::Polynomial;
  request.mapping.tiles = tiles;
  request.mapping.scale = scale;
  request.mapping.map_atoms = false;
  const auto parallel = two_threads();
  // Clicks at several places, nothing kept between them.
  std::vector<double> clicks;
  std::size_t disk_triangles = 0, level = 0;
  for (const std::int64_t vertex : { 1000, 250000, 500000, 750000, 1000000 })
  {
    const auto seed = mapper->seed_near(mapper->surface().mesh().point(vertex));
    mapper->forget_charts();
    mesolens::MapResult result;
    clicks.push_back(seconds_of([&] { result = mapper->map(seed, patch, request, parallel); }));
    std::printf("REPORT remap-click vertex %lld: %.1f ms, disk of %zu triangles on copy %zu, %s "
                "pieces, k = %d%s%s\n",
                static_cast<long long>(vertex), 1e3 * clicks.back(),
                result.chart->disk.mesh.triangle_count(), result.chart->disk.surface_level,
                pieces_of(result.mapped).c_str(), result.tiles_mapped,
                result.note.empty() ? "" : ": ", result.note.c_str());
    if (vertex == 1000)
    {
      disk_triangles = result.chart->disk.mesh.triangle_count();
      level = result.chart->disk.surface_level;
    }
  }
  // The steps of the first click.
  const auto seed = mapper->seed_near(mapper->surface().mesh().point(1000));
  mesolens::GeodesicDiskParams disk_params;
  disk_params.radius = radius;
  mesolens::GeodesicDisk disk;
  const double geodesic = median_seconds(
    3, [&] { disk = mesolens::geodesic_disk(mapper->surface(), seed, disk_params); });
  mesolens::DiskParameterization map;
  const double parameterization =
    median_seconds(3, [&] { map = mesolens::harmonic_parameterization(disk.mesh, radius); });
  std::unique_ptr<mesolens::SurfaceChart> chart;
  const double chart_build = median_seconds(3, [&] {
    chart = std::make_unique<mesolens::SurfaceChart>(
      disk.mesh, map.uv, disk.normals, mesolens::smooth_placement(disk, mapper->surface()));
  });
  mesolens::MappingParams params = request.mapping;
  params.centre_uv = chart->uv_of(disk.seed);
  mesolens::MappedMembrane fitted;
  const double fits =
    median_seconds(3, [&] { fitted = mesolens::map_membrane(*chart, patch, params, parallel); });
  const double cgal = cgal_parameterization_seconds(disk.mesh);
  std::printf(
    "BENCH remap input=%zu-triangle mesh, 15x15 tiles of YiiP (scale %.2e µm/Å, disk radius "
    "%.2f µm), 5 clicks on 2 threads | re-map median %.1f ms, max %.1f ms (goal 100 ms, ratio "
    "%.2f) | first click: disk of %zu triangles on coarser copy %zu: geodesic disk %.1f ms + "
    "parameterization %.1f ms + chart %.1f ms + 225 polynomial fits (%s pieces) %.1f ms | "
    "CGAL mean-value parameterization of the same disk %.1f ms, ratio ours/CGAL %.2f\n",
    triangles, scale, radius, 1e3 * percentile(clicks, 0.5),
    1e3 * *std::max_element(clicks.begin(), clicks.end()), percentile(clicks, 0.5) / 0.1,
    disk_triangles, level, 1e3 * geodesic, 1e3 * parameterization, 1e3 * chart_build,
    pieces_of(fitted).c_str(), 1e3 * fits, 1e3 * cgal, parameterization / cgal);
  if (smoke)
  {
    return;
  }

  // What the coarser copy changes: the same disk solved at the input's full resolution, both
  // charts turned alike (as the mapper turns them: u along the mesh's x axis).
  mesolens::GeodesicDiskParams full_params = disk_params;
  full_params.max_triangles = 0;
  mesolens::GeodesicDisk full;
  const double full_geodesic =
    seconds_of([&] { full = mesolens::geodesic_disk(mapper->surface(), seed, full_params); });
  mesolens::DiskParameterization full_map;
  const double full_parameterization =
    seconds_of([&] { full_map = mesolens::harmonic_parameterization(full.mesh, radius); });
  const double full_cgal = cgal_parameterization_seconds(full.mesh);
  mapper->forget_charts();
  const auto coarse_chart = mapper->chart(seed, radius);
  const auto full_chart = mapper->chart(seed, radius, 2000, 0);
  std::printf("BENCH remap-full-resolution input=the same disk on all %zu triangles of its "
              "region | geodesic disk %.0f ms + parameterization %.0f ms | CGAL %.0f ms, ratio "
              "ours/CGAL %.2f\n",
              full.mesh.triangle_count(), 1e3 * full_geodesic, 1e3 * full_parameterization,
              1e3 * full_cgal, full_parameterization / full_cgal);
  std::printf("REPORT remap-distortion coarse copy %zu (%zu triangles) vs full resolution (%zu) "
              "| angle distortion median %.4f vs %.4f, 95th percentile %.4f vs %.4f | "
              "|log area distortion| median %.4f vs %.4f, 95th percentile %.4f vs %.4f\n",
              disk.surface_level, disk.mesh.triangle_count(), full.mesh.triangle_count(),
              percentile(map.angle_distortion, 0.5), percentile(full_map.angle_distortion, 0.5),
              percentile(map.angle_distortion, 0.95), percentile(full_map.angle_distortion, 0.95),
              percentile(log_area(map.area_distortion), 0.5),
              percentile(log_area(full_map.area_distortion), 0.5),
              percentile(log_area(map.area_distortion), 0.95),
              percentile(log_area(full_map.area_distortion), 0.95));
  // Bond lengths of the YiiP tiles displaced on both charts, and how far the atoms move.
  mesolens::MappingParams displace = params;
  displace.method = mesolens::MappingMethod::Displacement;
  displace.max_polynomial_residual = 0;
  displace.centre_uv = coarse_chart->seed_uv;
  const auto coarse_atoms = mesolens::map_membrane(coarse_chart->chart, patch, displace, parallel);
  displace.centre_uv = full_chart->seed_uv;
  const auto full_atoms = mesolens::map_membrane(full_chart->chart, patch, displace, parallel);
  const auto coarse_bonds =
    absolute(mesolens::bond_length_changes(patch, coarse_atoms, yiip.bonds, scale));
  const auto full_bonds =
    absolute(mesolens::bond_length_changes(patch, full_atoms, yiip.bonds, scale));
  std::vector<double> moved;
  for (std::size_t i = 0; i < coarse_atoms.positions.size(); i += 3 * 97)
  {
    moved.push_back(
      std::sqrt(std::pow(coarse_atoms.positions[i] - full_atoms.positions[i], 2) +
                std::pow(coarse_atoms.positions[i + 1] - full_atoms.positions[i + 1], 2) +
                std::pow(coarse_atoms.positions[i + 2] - full_atoms.positions[i + 2], 2)) /
      scale);
  }
  std::printf("REPORT remap-bonds 15x15 YiiP displaced, coarse copy vs full resolution | "
              "|bond length change| median %.2e vs %.2e, 95th percentile %.2e vs %.2e, max %.2e "
              "vs %.2e | atoms placed apart by median %.1f Å, 95th percentile %.1f Å (of a %.0f Å "
              "wide tiling)\n",
              percentile(coarse_bonds, 0.5), percentile(full_bonds, 0.5),
              percentile(coarse_bonds, 0.95), percentile(full_bonds, 0.95),
              percentile(coarse_bonds, 1.0), percentile(full_bonds, 1.0), percentile(moved, 0.5),
              percentile(moved, 0.95), tiles * yiip.width());
  // The paper's largest case evaluated on the CPU: every atom of every tile by its polynomial.
  mesolens::MappingParams evaluate = params;
  evaluate.map_atoms = true;
  mesolens::MappedMembrane mapped;
  const double evaluation =
    seconds_of([&] { mapped = mesolens::map_membrane(*chart, patch, evaluate); }) - fits;
  const double atoms = double(mapped.positions.size() / 3);
  std::printf("BENCH cpu-evaluation input=15x15 tiles x %zu atoms = %.0f atoms (polynomial, %s "
              "pieces per tile) | %.0f ms, %.1f Matoms/s (single thread)\n",
              patch.atom_count(), atoms, pieces_of(mapped).c_str(), 1e3 * evaluation,
              atoms / evaluation / 1e6);
}

/// The interactive case: the organelle mesh as it comes (8340 triangles), refined locally.
void remap_interactive(const Membrane& yiip)
{
  const mesolens::MembraneMapper mapper(
    to_mesh(read_obj(mesolens_test::data_file("meshes/mito5_outer_membrane.obj"), 0)));
  const auto seed = mapper.seed_near(mapper.surface().mesh().point(1000));
  const auto patch = yiip.patch();
  for (const auto& [label, k, factor] :
       { std::make_tuple("15x15 tiles (disk radius 0.12 µm)", 15, 0.12 / (30 * yiip.width())),
         std::make_tuple("3x3 tiles at true scale (1e-4 µm/Å)", 3, 1e-4) })
  {
    mesolens::MapRequest request;
    request.mapping.method = mesolens::MappingMethod::Polynomial;
    request.mapping.tiles = k;
    request.mapping.scale = factor;
    request.mapping.map_atoms = false;
    mesolens::MapResult result;
    const double remap = median_seconds(5, [&] {
      mapper.forget_charts();
      result = mapper.map(seed, patch, request, two_threads());
    });
    std::printf("BENCH remap-interactive input=mito5_outer_membrane (8340 triangles), YiiP %s, "
                "disk of %zu triangles (input triangles halved up to %d times) | re-map %.1f ms "
                "on 2 threads (goal 100 ms), %s polynomial pieces per tile\n",
                label, result.chart->disk.mesh.triangle_count(),
                result.chart->disk.refinement_levels, 1e3 * remap,
                pieces_of(result.mapped).c_str());
  }
}
} // namespace

int main(int argc, char* argv[])
{
  using mesolens_test::data_file;
  const bool smoke = argc > 1 && std::string(argv[1]) == "--smoke";
  const Membrane yiip = read_membrane(data_file("membranes/yiip_popepopg.gro"));
  remap_on_two_million(yiip, smoke);
  remap_interactive(yiip);
  if (smoke)
  {
    return 0;
  }
  const Membrane dppc = read_membrane(data_file("membranes/dppc128_slipids_323K.gro"));
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
