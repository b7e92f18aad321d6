// SPDX-License-Identifier: GPL-3.0-or-later
// Membrane-mapping robustness benchmark: how often, how fast and how well a click maps a
// membrane onto any cell mesh, through mesolens::MembraneMapper as the viewer maps one.
//
// Inputs: every mesh file directly in Data/meshes and ../shared/data/meshes (each file name
// once; the bad/ folders left out), and synthetic ones: closed surfaces of genus 1, 5, 20 and 50
// made of 80 nm thick bars around holes, a 1 µm icosahedron of 20 triangles, a 5 µm capsule of
// radius 50 nm, and the mitochondrion's outer membrane Loop-subdivided to 2 M triangles. Every
// flat periodic bilayer of Data/membranes (waters and ions removed, molecules made whole) at
// true scale, 1e-4 µm/Å. On each mesh 20 clicks (farthest-point samples of its vertices from the
// first one; the icosahedron has only 12 vertices), 1, 3, 5 and 15 tiles, all three methods. To
// keep the full run near 30 min on 2 cores, the 2 M-triangle mesh gets 5 clicks and bond lengths
// are measured on the first 5 clicks of each mesh (printed as robustness-reduced lines).
//
// Per mesh x membrane and in total it prints:
//  - the share of cases that map something (goal 100 %) and that map the asked k x k tiles;
//  - the time of one MembraneMapper::map with no chart cached, on 2 threads: polynomial and
//    instancing without atoms, as the renderer uses them (goal: median <= 100 ms, max <= 1 s);
//    displacement apart, since it maps every atom and grows with their count;
//  - the largest distance of the mapped mid-sheet (patch points at height 0) from the input mesh
//    and from the smooth surface the mapper maps onto; |bond-length change| per method (from a
//    separate, untimed call that maps the atoms); the polynomial's fit residuals, splits and
//    displacement fallbacks;
//  - determinism: each case mapped on 1 and on 2 threads, each with an empty chart cache, and
//    the outputs (positions, instance matrices, polynomial coefficients) compared bitwise.
// Then every failure message and every note saying that fewer tiles were mapped, grouped, each
// with one case and the command that maps it again.
//
//   BenchmarkMappingRobustness [--smoke] [--clicks N] [--mesh NAME] [--membrane NAME]
//                              [--tiles K] [--method displacement|instancing|polynomial]
//
// --smoke (CI): mito5_outer_membrane and the icosahedron, the Martini bilayer, 2 clicks, 1 and 3
// tiles. The other options select the clicks, one mesh, membrane, tile count or method. It never
// asserts on time or quality; it exits non-zero only when an input of Data/ cannot be read.
#include "mesolens/common/errors.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/mesh/mesh_report.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/molecules/molecule_pbc.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/mesh/surface_locator.h"
#include "mesolens/mesh/triangle_mesh.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_threads.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoMeshReader.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCleanPolyData.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLoopSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {
using mesolens::MappingMethod;
using mesolens_test::seconds_of;

// Every mesh is taken in µm. The mitochondrion meshes state it; hipsc_mean_nucleus, the
// C. elegans cells (and the CGAL patch) state no unit and are assumed to be in µm as well.
constexpr double micron_per_angstrom = 1e-4;
constexpr double nanometres_per_micron = 1e3;
constexpr double goal_median_seconds = 0.1;
constexpr double goal_max_seconds = 1.0;
constexpr std::size_t bond_sample_per_case = 20000;
const char* const method_names[] = { "displacement", "instancing", "polynomial" };

struct Options
{
  bool smoke = false;
  int clicks = 20;
  std::vector<int> tiles{ 1, 3, 5, 15 };
  std::vector<int> methods{ 0, 1, 2 };
  std::string mesh;     ///< only this mesh (empty: all)
  std::string membrane; ///< only this membrane (empty: all)
  int bond_clicks = 5;  ///< bond lengths are measured on the first clicks of each mesh only
};

std::string text_argument(int argc, char* argv[], const char* name)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (!std::strcmp(argv[i], name))
    {
      return argv[i + 1];
    }
  }
  return "";
}

Options parse_options(int argc, char* argv[])
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    options.smoke = options.smoke || !std::strcmp(argv[i], "--smoke");
  }
  if (options.smoke)
  {
    options.clicks = 2;
    options.tiles = { 1, 3 };
  }
  options.clicks = mesolens_test::count_argument(argc, argv, "--clicks", options.clicks);
  if (options.smoke)
  {
    options.bond_clicks = options.clicks;
  }
  const std::string tiles = text_argument(argc, argv, "--tiles");
  if (!tiles.empty())
  {
    options.tiles = { std::max(1, std::atoi(tiles.c_str())) };
  }
  const std::string method = text_argument(argc, argv, "--method");
  for (int m = 0; m < 3; ++m)
  {
    if (method == method_names[m])
    {
      options.methods = { m };
    }
  }
  options.mesh = text_argument(argc, argv, "--mesh");
  options.membrane = text_argument(argc, argv, "--membrane");
  return options;
}

double percentile(std::vector<double> values, double p)
{
  if (values.empty())
  {
    return std::nan("");
  }
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, std::size_t(p * double(values.size())))];
}

double share(std::size_t part, std::size_t whole)
{
  return whole ? 100.0 * double(part) / double(whole) : 0.0;
}

/// A file's name without folder and extension.
std::string stem(const std::string& path)
{
  const std::string name = path.substr(path.find_last_of('/') + 1);
  return name.substr(0, name.find_last_of('.'));
}

/// The files directly in `folder` whose extension is one of `extensions` (sorted; none when the
/// folder is absent).
std::vector<std::string> files_in(const std::string& folder,
                                  const std::set<std::string>& extensions)
{
  std::vector<std::string> names;
  if (DIR* directory = opendir(folder.c_str()))
  {
    while (const dirent* entry = readdir(directory))
    {
      const std::string name = entry->d_name;
      const std::size_t dot = name.find_last_of('.');
      if (dot != std::string::npos && extensions.count(name.substr(dot + 1)))
      {
        names.push_back(name);
      }
    }
    closedir(directory);
  }
  std::sort(names.begin(), names.end());
  return names;
}

// ---------------------------------------------------------------------------------------------
// Meshes

/// The polygons of a polydata as triangles (fans for larger polygons).
mesolens::TriangleMesh triangle_mesh(vtkPolyData* surface)
{
  mesolens::TriangleMesh mesh;
  mesh.points.resize(3 * std::size_t(surface->GetNumberOfPoints()));
  for (vtkIdType v = 0; v < surface->GetNumberOfPoints(); ++v)
  {
    surface->GetPoint(v, mesh.points.data() + 3 * v);
  }
  auto cells = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(size, ids);
    for (vtkIdType k = 2; k < size; ++k)
    {
      mesh.triangles.insert(mesh.triangles.end(), { ids[0], ids[k - 1], ids[k] });
    }
  }
  return mesh;
}

/// A mesh file read by vtkMesoMeshReader; null with `error` set when it cannot be read.
vtkSmartPointer<vtkPolyData> read_surface(const std::string& path, std::string& error)
{
  vtkNew<vtkMesoMeshReader> reader;
  reader->SetFileName(path.c_str());
  mesolens_test::EventRecorder events(reader);
  reader->Update();
  if (!events.Errors.empty() || reader->GetOutput()->GetNumberOfPolys() == 0)
  {
    error = events.Errors.empty() ? "no polygons in " + path : events.Errors.front();
    return nullptr;
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->ShallowCopy(reader->GetOutput());
  return surface;
}

/// Turns every triangle around when the mesh encloses a negative volume (normals inwards).
void orient_outwards(mesolens::TriangleMesh& mesh)
{
  double volume = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto a = mesh.point(mesh.triangles[3 * t]);
    const auto b = mesh.point(mesh.triangles[3 * t + 1]);
    const auto c = mesh.point(mesh.triangles[3 * t + 2]);
    volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  if (volume < 0)
  {
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    {
      std::swap(mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]);
    }
  }
}

struct Segment
{
  std::array<double, 3> from, to;
};

double distance_to_segment(const std::array<double, 3>& p, const Segment& s)
{
  std::array<double, 3> d{}, w{};
  double dd = 0, wd = 0;
  for (int k = 0; k < 3; ++k)
  {
    d[k] = s.to[k] - s.from[k];
    w[k] = p[k] - s.from[k];
    dd += d[k] * d[k];
    wd += w[k] * d[k];
  }
  const double t = dd > 0 ? std::clamp(wd / dd, 0.0, 1.0) : 0.0;
  return std::hypot(w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]);
}

/// The closed surface at distance `radius` from `segments` (the union of round tubes with round
/// ends around them): the distance sampled `spacing` apart on a vtkImageData, contoured by
/// vtkFlyingEdges3D, cleaned, oriented outwards.
mesolens::TriangleMesh tube_union(const std::vector<Segment>& segments, double radius,
                                  double spacing)
{
  std::array<double, 3> low{}, high{};
  for (int k = 0; k < 3; ++k)
  {
    low[k] = high[k] = segments.front().from[k];
    for (const Segment& s : segments)
    {
      low[k] = std::min({ low[k], s.from[k], s.to[k] });
      high[k] = std::max({ high[k], s.from[k], s.to[k] });
    }
    // Off the grid by an odd fraction of a step, so that no sample lies exactly on the surface
    // (zero values give the contour coincident points, degenerate and non-manifold triangles).
    low[k] -= radius + (3 + 0.382 + 0.1 * k) * spacing;
    high[k] += radius + 3 * spacing;
  }
  vtkNew<vtkImageData> samples;
  samples->SetOrigin(low.data());
  samples->SetSpacing(spacing, spacing, spacing);
  int dimensions[3];
  for (int k = 0; k < 3; ++k)
  {
    dimensions[k] = int(std::ceil((high[k] - low[k]) / spacing)) + 1;
  }
  samples->SetDimensions(dimensions);
  samples->AllocateScalars(VTK_FLOAT, 1);
  auto* values = vtkFloatArray::SafeDownCast(samples->GetPointData()->GetScalars());
  for (vtkIdType id = 0; id < samples->GetNumberOfPoints(); ++id)
  {
    std::array<double, 3> p{};
    samples->GetPoint(id, p.data());
    double nearest = std::numeric_limits<double>::infinity();
    for (const Segment& s : segments)
    {
      nearest = std::min(nearest, distance_to_segment(p, s));
    }
    values->SetValue(id, float(nearest - radius));
  }
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(samples);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(contour->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->Update();
  mesolens::TriangleMesh mesh = triangle_mesh(clean->GetOutput());
  orient_outwards(mesh);
  return mesh;
}

/// Bars along the lines of a grid of `columns` x `rows` square holes `pitch` apart: thickened,
/// a closed surface of genus columns x rows.
std::vector<Segment> hole_grid(int columns, int rows, double pitch)
{
  std::vector<Segment> bars;
  for (int i = 0; i <= columns; ++i)
  {
    bars.push_back({ { i * pitch, 0, 0 }, { i * pitch, rows * pitch, 0 } });
  }
  for (int j = 0; j <= rows; ++j)
  {
    bars.push_back({ { 0, j * pitch, 0 }, { columns * pitch, j * pitch, 0 } });
  }
  return bars;
}

/// A mesh to map onto: how to make it, and what it is.
struct MeshSource
{
  std::string name;
  std::string what;
  std::function<vtkSmartPointer<vtkPolyData>(std::string&)> read; ///< a file (null: made)
  std::function<mesolens::TriangleMesh()> make;
  bool required = false;   ///< from Data/: the benchmark fails when it cannot be read
  int expected_genus = -1; ///< synthetic: the genus it is built with
  int max_clicks = 0;      ///< > 0: fewer clicks than asked (to keep the run short)
};

/// Every mesh file directly in Data/meshes and the shared meshes folder, each name once.
void add_mesh_files(std::vector<MeshSource>& sources)
{
  std::set<std::string> seen;
  const std::set<std::string> extensions{ "obj", "ply", "stl", "vtp", "off" };
  for (const std::string& folder :
       { mesolens_test::data_file("meshes"), mesolens_test::shared_file("meshes") })
  {
    const bool required = folder == mesolens_test::data_file("meshes");
    if (!required && !mesolens_test::exists(folder))
    {
      std::printf("REPORT robustness-input %s is absent: its meshes are skipped\n", folder.c_str());
    }
    for (const std::string& file : files_in(folder, extensions))
    {
      if (seen.insert(file).second)
      {
        const std::string path = folder + "/" + file;
        sources.push_back({ stem(file), path,
                            [path](std::string& error) { return read_surface(path, error); },
                            nullptr, required });
      }
    }
  }
}

/// The 2 M-triangle mesh: the mitochondrion's outer membrane Loop-subdivided 4 times.
vtkSmartPointer<vtkPolyData> subdivided_mitochondrion(std::string& error)
{
  auto surface = read_surface(mesolens_test::data_file("meshes/mito5_outer_membrane.obj"), error);
  if (surface)
  {
    vtkNew<vtkLoopSubdivisionFilter> loop;
    loop->SetInputData(surface);
    loop->SetNumberOfSubdivisions(4);
    loop->Update();
    surface->ShallowCopy(loop->GetOutput());
  }
  return surface;
}

/// The synthetic meshes, in µm.
void add_synthetic_meshes(std::vector<MeshSource>& sources)
{
  // Bars of radius 40 nm (80 nm thick) around square holes, sampled every 10 nm.
  struct HoleGrid
  {
    int columns, rows;
    double pitch; // µm
  };
  for (const HoleGrid grid : { HoleGrid{ 1, 1, 1.5 }, HoleGrid{ 5, 1, 0.6 }, HoleGrid{ 5, 4, 0.5 },
                               HoleGrid{ 10, 5, 0.4 } })
  {
    char what[160];
    std::snprintf(what, sizeof what,
                  "synthetic: %d x %d holes %.1f µm apart in a frame of 80 nm bars", grid.columns,
                  grid.rows, grid.pitch);
    const int genus = grid.columns * grid.rows;
    sources.push_back(
      { "synthetic_genus" + std::to_string(genus), what, nullptr,
        [grid] { return tube_union(hole_grid(grid.columns, grid.rows, grid.pitch), 0.04, 0.01); },
        false, genus });
  }
  // Circumradius of an icosahedron whose edges are 1 µm long: 1 / (2 sin(2 pi / 5)).
  sources.push_back(
    { "synthetic_icosahedron", "synthetic: 20 triangles, edges of 1 µm", nullptr,
      [] { return mesolens_test::icosphere(0.5 / std::sin(0.4 * 3.14159265358979), 0); }, false,
      0 });
  sources.push_back({ "synthetic_capsule",
                      "synthetic: radius 50 nm, 5 µm long, sampled every 10 nm", nullptr,
                      [] {
                        return tube_union({ { { 0, 0, 0 }, { 4.9, 0, 0 } } }, 0.05, 0.01);
                      },
                      false, 0 });
  sources.push_back({ "mito5_outer_membrane_loop4", "mito5_outer_membrane Loop-subdivided 4 times",
                      subdivided_mitochondrion, nullptr, true, 0, 5 });
}

/// The meshes the options select.
std::vector<MeshSource> mesh_sources(const Options& options)
{
  std::vector<MeshSource> sources;
  add_mesh_files(sources);
  add_synthetic_meshes(sources);
  std::vector<MeshSource> selected;
  for (const MeshSource& source : sources)
  {
    const bool smoke_mesh =
      source.name == "mito5_outer_membrane" || source.name == "synthetic_icosahedron";
    if ((options.mesh.empty() || options.mesh == source.name) && (!options.smoke || smoke_mesh))
    {
      selected.push_back(source);
    }
  }
  return selected;
}

/// `count` vertices spread over the mesh: its first vertex used by a triangle, then again and
/// again the vertex farthest (Euclidean) from those already taken.
std::vector<std::int64_t> farthest_vertices(const mesolens::TriangleMesh& mesh, int count)
{
  std::vector<std::uint8_t> used(mesh.vertex_count(), 0);
  for (const std::int64_t v : mesh.triangles)
  {
    used[std::size_t(v)] = 1;
  }
  std::vector<double> nearest(mesh.vertex_count(), std::numeric_limits<double>::infinity());
  std::int64_t next = std::int64_t(std::find(used.begin(), used.end(), 1) - used.begin());
  std::vector<std::int64_t> chosen;
  while (int(chosen.size()) < count && next >= 0 && next < std::int64_t(used.size()))
  {
    chosen.push_back(next);
    const auto p = mesh.point(next);
    double farthest = 0;
    next = -1;
    for (std::size_t v = 0; v < used.size(); ++v)
    {
      const double* q = mesh.points.data() + 3 * v;
      const double d =
        std::pow(q[0] - p[0], 2) + std::pow(q[1] - p[1], 2) + std::pow(q[2] - p[2], 2);
      nearest[v] = std::min(nearest[v], d);
      if (used[v] && nearest[v] > farthest)
      {
        farthest = nearest[v];
        next = std::int64_t(v);
      }
    }
  }
  return chosen;
}

// ---------------------------------------------------------------------------------------------
// Membranes

/// A flat periodic bilayer patch (Å) with its bonds and a grid of mid-sheet points.
struct Membrane
{
  std::string name;
  mesolens::AtomTable table;
  std::vector<std::array<std::uint32_t, 2>> bonds;
  std::vector<float> mid_sheet_points; ///< 7 x 7 points over the cell at the bilayer's centre
  double centre_height = 0;
  std::size_t atoms_read = 0;
  std::size_t molecules = 0;
  double axis_alignment = 0; ///< mean |cos| of the molecules' axes to z

  mesolens::MembranePatch patch() const
  {
    mesolens::MembranePatch p;
    p.positions = this->table.positions;
    p.molecule_ids = this->table.molecule_ids.data();
    p.a = { this->table.box.vectors[0][0], this->table.box.vectors[0][1] };
    p.b = { this->table.box.vectors[1][0], this->table.box.vectors[1][1] };
    p.centre_height = this->centre_height;
    return p;
  }
  /// The same cell holding only the mid-sheet points (each its own molecule).
  mesolens::MembranePatch mid_sheet() const
  {
    mesolens::MembranePatch p = this->patch();
    p.positions = this->mid_sheet_points;
    p.molecule_ids = nullptr;
    return p;
  }
};

/// Mean |cos| of the angle between z and each molecule's axis (its centroid to its first atom,
/// the head group of a lipid): near 1 for a flat bilayer in the xy plane, about 1/2 for a
/// vesicle, whose lipids point every way.
double axis_alignment(const mesolens::AtomTable& table)
{
  std::map<int, std::array<double, 7>> molecules; // centroid sum, count, first atom
  for (std::size_t a = 0; a < table.size(); ++a)
  {
    auto [entry, added] = molecules.try_emplace(table.molecule_ids[a]);
    auto& m = entry->second;
    for (int k = 0; k < 3; ++k)
    {
      m[std::size_t(k)] += table.positions[3 * a + std::size_t(k)];
      if (added)
      {
        m[std::size_t(4 + k)] = table.positions[3 * a + std::size_t(k)];
      }
    }
    m[3] += 1;
  }
  double sum = 0;
  for (const auto& [id, m] : molecules)
  {
    const double x = m[4] - m[0] / m[3], y = m[5] - m[1] / m[3], z = m[6] - m[2] / m[3];
    const double length = std::hypot(x, y, z);
    sum += length > 0 ? std::abs(z) / length : 0;
  }
  return molecules.empty() ? 0 : sum / double(molecules.size());
}

/// Reads a .gro membrane: molecules made whole across the box, bonds perceived on them, waters
/// and ions (molecules of one atom) removed. Throws as read_gro_topology().
Membrane read_membrane(const std::string& path)
{
  Membrane membrane;
  membrane.name = stem(path);
  mesolens::AtomTable table = mesolens::read_gro_topology(path);
  membrane.atoms_read = table.size();
  mesolens::assign_residues(table);
  mesolens::assign_molecules(table);
  mesolens::make_molecules_whole(table.positions, table.molecule_ids.data(), table.box);
  mesolens::build_connectivity(table, {}, mesolens::StructureReadParams{}, false);
  std::map<int, std::size_t> atoms_of;
  for (const int id : table.molecule_ids)
  {
    ++atoms_of[id];
  }
  // Ions: molecules of one atom, and multi-site ion models such as YiiP's zinc (ZNM: a Zn with
  // dummy atoms).
  const std::set<std::string> ions{ "ZN", "ZNM", "NA",  "CL",  "K",   "MG",
                                    "CA", "SOD", "CLA", "POT", "CAL", "ION" };
  std::vector<bool> keep(table.size());
  for (std::size_t a = 0; a < table.size(); ++a)
  {
    keep[a] = !mesolens::is_water_residue(table.residue_names[a]) &&
      !ions.count(table.residue_names[a]) && atoms_of[table.molecule_ids[a]] > 1;
  }
  table.filter(keep);
  membrane.table = std::move(table);
  for (const mesolens::Bond& b : membrane.table.bonds)
  {
    membrane.bonds.push_back({ b.first, b.second });
  }
  for (std::size_t a = 0; a < membrane.table.size(); ++a)
  {
    membrane.centre_height += membrane.table.positions[3 * a + 2] / double(membrane.table.size());
  }
  membrane.molecules =
    std::set<int>(membrane.table.molecule_ids.begin(), membrane.table.molecule_ids.end()).size();
  membrane.axis_alignment = axis_alignment(membrane.table);
  const auto& box = membrane.table.box.vectors;
  for (int j = 0; j <= 6; ++j)
  {
    for (int i = 0; i <= 6; ++i)
    {
      membrane.mid_sheet_points.insert(membrane.mid_sheet_points.end(),
                                       { float(i / 6.0 * box[0][0] + j / 6.0 * box[1][0]),
                                         float(i / 6.0 * box[0][1] + j / 6.0 * box[1][1]),
                                         float(membrane.centre_height) });
    }
  }
  return membrane;
}

/// The flat periodic bilayers of Data/membranes; the others are listed as not applicable.
/// Returns false when a file cannot be read.
bool read_membranes(const Options& options, std::vector<Membrane>& membranes)
{
  const std::string folder = mesolens_test::data_file("membranes");
  const std::vector<std::string> files = files_in(folder, { "gro" });
  if (files.empty())
  {
    std::printf("REPORT robustness-input no .gro membrane in %s\n", folder.c_str());
    return false;
  }
  for (const std::string& file : files)
  {
    const bool smoke_membrane = stem(file) == "martini_dppc_chol_bilayer";
    if ((!options.membrane.empty() && options.membrane != stem(file)) ||
        (options.smoke && !smoke_membrane))
    {
      continue;
    }
    Membrane membrane;
    try
    {
      membrane = read_membrane(folder + "/" + file);
    }
    catch (const std::exception& e)
    {
      std::printf("REPORT robustness-input cannot read %s: %s\n", file.c_str(), e.what());
      return false;
    }
    // A flat patch: a periodic box and molecules standing along z (a vesicle's lipids point every
    // way).
    const bool flat = membrane.table.box.is_set() && membrane.axis_alignment > 0.7;
    const auto& box = membrane.table.box.vectors;
    std::printf("BENCH robustness-membrane %s: %zu of %zu atoms kept (waters and ions removed), "
                "%zu molecules, cell %.1f x %.1f Å, mean |cos(molecule axis, z)| %.2f: %s\n",
                membrane.name.c_str(), membrane.table.size(), membrane.atoms_read,
                membrane.molecules, std::hypot(box[0][0], box[0][1]),
                std::hypot(box[1][0], box[1][1]), membrane.axis_alignment,
                flat ? "a flat periodic patch" : "not applicable (not a flat periodic patch)");
    if (flat)
    {
      membranes.push_back(std::move(membrane));
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Cases

/// One message group: how often, and the first case that gave it.
struct Occurrences
{
  std::size_t count = 0;
  std::string example;
};

struct MessageLog
{
  std::map<std::string, Occurrences> failures;
  std::map<std::string, Occurrences> notes;

  /// Counts `message` under its text with every number replaced by '#'.
  static void add(std::map<std::string, Occurrences>& groups, const std::string& message,
                  const std::string& example)
  {
    static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
    std::string one_line = message;
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    Occurrences& group = groups[std::regex_replace(one_line, number, "#")];
    if (group.count++ == 0)
    {
      group.example = example + ": " + one_line;
    }
  }
};

/// The largest value of a figure and the case that gave it.
struct Worst
{
  double value = 0;
  std::string at;
  void offer(double candidate, const std::string& where)
  {
    if (candidate > this->value)
    {
      this->value = candidate;
      this->at = where;
    }
  }
};

/// What one method's cases gave.
struct MethodTally
{
  std::vector<double> seconds;
  std::vector<double> cached_seconds; ///< the same maps with their disks cached
  std::vector<double> bond_sample;    ///< |change|, up to bond_sample_per_case per case
  double bond_max = 0;
  double mid_sheet_from_input = 0;  ///< largest, mesh units
  double mid_sheet_from_smooth = 0; ///< largest, mesh units
};

/// What the cases of a mesh x membrane (or all) gave.
struct Tally
{
  std::size_t cases = 0, mapped = 0, asked = 0, cut = 0;
  std::map<int, std::array<std::size_t, 2>> asked_by_tiles; ///< k -> {asked k mapped, cases}
  std::array<MethodTally, 3> methods;
  std::vector<double> residuals; ///< polynomial_max_residual per tile, Å
  double kept_residual_max = 0;  ///< the same over tiles kept as polynomials, Å
  std::size_t polynomial_maps = 0, split_maps = 0, polynomial_tiles = 0, split_tiles = 0;
  std::size_t fallback_tiles = 0;
  std::size_t compared = 0, mismatches = 0;
  double wall_seconds = 0; ///< everything the cases took, measurements included
  double slowest = 0;      ///< the slowest polynomial or instancing map, seconds
  Worst worst_bond;        ///< the largest |bond-length change|
  Worst worst_mid_sheet;   ///< the largest distance of the mid-sheet from the input mesh
  std::string slowest_case;

  void add(const Tally& other)
  {
    cases += other.cases, mapped += other.mapped, asked += other.asked, cut += other.cut;
    for (const auto& [k, counts] : other.asked_by_tiles)
    {
      asked_by_tiles[k][0] += counts[0];
      asked_by_tiles[k][1] += counts[1];
    }
    for (std::size_t m = 0; m < 3; ++m)
    {
      MethodTally& mine = methods[m];
      const MethodTally& theirs = other.methods[m];
      mine.seconds.insert(mine.seconds.end(), theirs.seconds.begin(), theirs.seconds.end());
      mine.bond_sample.insert(mine.bond_sample.end(), theirs.bond_sample.begin(),
                              theirs.bond_sample.end());
      mine.bond_max = std::max(mine.bond_max, theirs.bond_max);
      mine.mid_sheet_from_input = std::max(mine.mid_sheet_from_input, theirs.mid_sheet_from_input);
      mine.mid_sheet_from_smooth =
        std::max(mine.mid_sheet_from_smooth, theirs.mid_sheet_from_smooth);
      mine.cached_seconds.insert(mine.cached_seconds.end(), theirs.cached_seconds.begin(),
                                 theirs.cached_seconds.end());
    }
    residuals.insert(residuals.end(), other.residuals.begin(), other.residuals.end());
    kept_residual_max = std::max(kept_residual_max, other.kept_residual_max);
    polynomial_maps += other.polynomial_maps, split_maps += other.split_maps;
    split_tiles += other.split_tiles;
    polynomial_tiles += other.polynomial_tiles, fallback_tiles += other.fallback_tiles;
    compared += other.compared, mismatches += other.mismatches;
    wall_seconds += other.wall_seconds;
    worst_bond.offer(other.worst_bond.value, other.worst_bond.at);
    worst_mid_sheet.offer(other.worst_mid_sheet.value, other.worst_mid_sheet.at);
    if (other.slowest > slowest)
    {
      slowest = other.slowest;
      slowest_case = other.slowest_case;
    }
  }
};

/// A click on one mesh with one membrane.
struct Click
{
  const mesolens::MembraneMapper& mapper;
  const Membrane& membrane;
  std::string mesh_name;
  int index = 0; ///< among the mesh's clicks
  std::int64_t vertex = 0;
  bool measure_bonds = true;
  mesolens::SurfacePoint seed;

  std::string name(int tiles, int method) const
  {
    return "mesh=" + this->mesh_name + " membrane=" + this->membrane.name + " click " +
      std::to_string(this->index) + " (vertex " + std::to_string(this->vertex) +
      ") tiles=" + std::to_string(tiles) + " method=" + method_names[method];
  }
  /// The name and the command that maps the case again.
  std::string describe(int tiles, int method) const
  {
    return this->name(tiles, method) + " [reproduce: BenchmarkMappingRobustness --mesh " +
      this->mesh_name + " --membrane " + this->membrane.name + " --clicks " +
      std::to_string(this->index + 1) + " --tiles " + std::to_string(tiles) + " --method " +
      method_names[method] + "]";
  }
};

std::string error_text(const std::exception& e)
{
  const char* kind = dynamic_cast<const mesolens::OutsideChart*>(&e) ? "OutsideChart"
    : dynamic_cast<const mesolens::InvalidInput*>(&e)                ? "InvalidInput"
    : dynamic_cast<const mesolens::TopologyError*>(&e)               ? "TopologyError"
    : dynamic_cast<const mesolens::SolverFailure*>(&e)               ? "SolverFailure"
    : dynamic_cast<const mesolens::Error*>(&e)                       ? "mesolens::Error"
                                                                     : "std::exception";
  return std::string(kind) + ": " + e.what();
}

/// MembraneMapper::map; returns "" or what it threw.
std::string try_map(const Click& click, const mesolens::MapRequest& request,
                    const mesolens::ParallelFor& parallel_for, mesolens::MapResult& result)
{
  try
  {
    result = click.mapper.map(click.seed, click.membrane.patch(), request, parallel_for);
    return "";
  }
  catch (const std::exception& e)
  {
    return error_text(e);
  }
}

template<typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() &&
    (a.empty() || !std::memcmp(a.data(), b.data(), a.size() * sizeof(T)));
}

bool same_output(const mesolens::MapResult& x, const mesolens::MapResult& y)
{
  const mesolens::MappedMembrane& a = x.mapped;
  const mesolens::MappedMembrane& b = y.mapped;
  return x.tiles_mapped == y.tiles_mapped && x.cut_to_disk == y.cut_to_disk && x.note == y.note &&
    same_bits(a.positions, b.positions) && same_bits(a.instance_matrices, b.instance_matrices) &&
    same_bits(a.instance_molecules, b.instance_molecules) &&
    same_bits(a.polynomial_coefficients, b.polynomial_coefficients) &&
    same_bits(a.polynomial_splits, b.polynomial_splits) &&
    same_bits(a.polynomial_first_piece, b.polynomial_first_piece) &&
    same_bits(a.tile_fallback, b.tile_fallback) && same_bits(a.atom_mapped, b.atom_mapped);
}

/// The distance (mesh units) from `p` to the smooth surface the mapper maps onto (the input's
/// curved PN triangles): Gauss-Newton steps on the patch of each triangle around the closest
/// point of the input's facets (the smooth surface bulges off the facets, so the patch holding
/// the closest point may be a neighbour's), barycentric coordinates kept inside the triangle.
double distance_to_smooth_surface(const mesolens::CellSurface& surface,
                                  const std::array<double, 3>& p)
{
  const mesolens::SurfacePoint start = surface.closest_point(p);
  const mesolens::SmoothSurface& smooth = surface.smooth();
  auto distance = [&p](const std::array<double, 3>& q) {
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                     (p[2] - q[2]) * (p[2] - q[2]));
  };
  auto on_patch = [&](std::int64_t triangle, double b1, double b2) {
    auto at = [&](double x, double y) {
      return smooth.evaluate(triangle, { 1 - x - y, x, y }).position;
    };
    for (int step = 0; step < 8; ++step)
    {
      const auto x = at(b1, b2);
      constexpr double h = 1e-6;
      const auto x1 = at(b1 + h, b2), x2 = at(b1, b2 + h);
      double a11 = 0, a12 = 0, a22 = 0, r1 = 0, r2 = 0;
      for (std::size_t d = 0; d < 3; ++d)
      {
        const double j1 = (x1[d] - x[d]) / h, j2 = (x2[d] - x[d]) / h;
        a11 += j1 * j1;
        a12 += j1 * j2;
        a22 += j2 * j2;
        r1 += j1 * (p[d] - x[d]);
        r2 += j2 * (p[d] - x[d]);
      }
      const double determinant = a11 * a22 - a12 * a12;
      if (!(determinant > 0))
      {
        break;
      }
      b1 = std::clamp(b1 + (a22 * r1 - a12 * r2) / determinant, 0.0, 1.0);
      b2 = std::clamp(b2 + (a11 * r2 - a12 * r1) / determinant, 0.0, 1.0 - b1);
    }
    return distance(at(b1, b2));
  };
  double best = on_patch(start.triangle, start.barycentric[1], start.barycentric[2]);
  const mesolens::TriangleMesh& mesh = surface.mesh();
  const mesolens::MeshAdjacency& adjacency = surface.adjacency();
  for (std::size_t k = 0; k < 3; ++k)
  {
    const auto v = std::size_t(mesh.triangles[3 * std::size_t(start.triangle) + k]);
    for (std::size_t i = adjacency.vertex_start[v]; i < adjacency.vertex_start[v + 1]; ++i)
    {
      best = std::min(best, on_patch(adjacency.vertex_triangles[i], 1.0 / 3, 1.0 / 3));
    }
  }
  return best;
}

/// The largest distances (mesh units) of the mapped mid-sheet from the input mesh and from the
/// smooth surface the mapper maps onto. Displacement: the surface points under the grid of
/// mid-sheet points; polynomial: each tile's polynomial at those points (height 0), tiles that fell
/// back left out.
std::array<double, 2> mid_sheet_distances(const Click& click, const mesolens::MapRequest& request,
                                          const mesolens::MapResult& result)
{
  const mesolens::MembranePatch grid = click.membrane.mid_sheet();
  mesolens::MappingParams params = request.mapping;
  params.method = MappingMethod::Displacement;
  params.tiles = result.tiles_mapped;
  params.centre_uv = result.chart->seed_uv;
  params.cut_to_disk = true; // grid points beyond the disk are left out
  const mesolens::MappedMembrane on_surface =
    mesolens::map_membrane(result.chart->chart, grid, params, mesolens_test::two_threads());
  const bool polynomial = request.mapping.method == MappingMethod::Polynomial;
  std::array<double, 2> largest{ 0, 0 };
  const std::size_t tiles = std::size_t(result.tiles_mapped) * std::size_t(result.tiles_mapped);
  for (std::size_t t = 0; t < tiles; ++t)
  {
    if (polynomial && result.mapped.tile_fallback[t])
    {
      continue;
    }
    for (std::size_t a = 0; a < grid.atom_count(); ++a)
    {
      const double* q = on_surface.positions.data() + 3 * (t * grid.atom_count() + a);
      if (!std::isfinite(q[0]))
      {
        continue;
      }
      std::array<double, 3> p{ q[0], q[1], q[2] };
      if (polynomial)
      {
        p = mesolens::evaluate_tile_polynomial(grid, params.layer_half_thickness,
                                               result.mapped.polynomial_splits[t],
                                               result.mapped.polynomial_coefficients.data() +
                                                 30 * result.mapped.polynomial_first_piece[t],
                                               grid.positions[a]);
      }
      double from_input = 0;
      click.mapper.surface().closest_point(p, &from_input);
      const double from_smooth = distance_to_smooth_surface(click.mapper.surface(), p);
      largest[0] = std::max(largest[0], from_input);
      largest[1] = std::max(largest[1], from_smooth);
    }
  }
  return largest;
}

/// |bond-length change| of the mapped atoms: the largest (returned and tallied), and an evenly
/// strided sample.
double add_bond_changes(const Click& click, const mesolens::MappedMembrane& mapped,
                        MethodTally& tally)
{
  const std::vector<double> changes = mesolens::bond_length_changes(
    click.membrane.patch(), mapped, click.membrane.bonds, micron_per_angstrom);
  const std::size_t stride = std::max<std::size_t>(1, changes.size() / bond_sample_per_case);
  double largest = 0;
  for (std::size_t i = 0; i < changes.size(); ++i)
  {
    const double change = std::abs(changes[i]);
    if (std::isfinite(change))
    {
      largest = std::max(largest, change);
      if (i % stride == 0)
      {
        tally.bond_sample.push_back(change);
      }
    }
  }
  tally.bond_max = std::max(tally.bond_max, largest);
  return largest;
}

void add_polynomial_fit(const mesolens::MappedMembrane& mapped, Tally& tally)
{
  ++tally.polynomial_maps;
  tally.split_maps += std::any_of(mapped.polynomial_splits.begin(), mapped.polynomial_splits.end(),
                                  [](int m) { return m > 1; });
  for (std::size_t t = 0; t < mapped.polynomial_max_residual.size(); ++t)
  {
    const double residual = mapped.polynomial_max_residual[t] / micron_per_angstrom;
    tally.residuals.push_back(residual);
    ++tally.polynomial_tiles;
    tally.split_tiles += mapped.polynomial_splits[t] > 1 ? 1 : 0;
    if (mapped.tile_fallback[t])
    {
      ++tally.fallback_tiles;
    }
    else
    {
      tally.kept_residual_max = std::max(tally.kept_residual_max, residual);
    }
  }
}

/// The untimed measurements of a mapped case: mid-sheet, bonds (atoms mapped in a separate
/// call for the methods that leave them to the renderer), polynomial fit.
void measure_quality(const Click& click, mesolens::MapRequest request,
                     const mesolens::MapResult& result, Tally& tally, MessageLog& log)
{
  const MappingMethod method = request.mapping.method;
  MethodTally& tallied = tally.methods[std::size_t(method)];
  const std::string name = click.name(request.mapping.tiles, int(method));
  try
  {
    if (method != MappingMethod::MoleculeInstancing)
    {
      const auto distances = mid_sheet_distances(click, request, result);
      tallied.mid_sheet_from_input = std::max(tallied.mid_sheet_from_input, distances[0]);
      tallied.mid_sheet_from_smooth = std::max(tallied.mid_sheet_from_smooth, distances[1]);
      tally.worst_mid_sheet.offer(distances[0], name);
    }
    if (method == MappingMethod::Polynomial)
    {
      add_polynomial_fit(result.mapped, tally);
    }
    if (!click.measure_bonds)
    {
      return;
    }
    mesolens::MapResult with_atoms;
    if (method != MappingMethod::Displacement)
    {
      request.mapping.map_atoms = true;
      const std::string failure = try_map(click, request, mesolens_test::two_threads(), with_atoms);
      if (!failure.empty())
      {
        MessageLog::add(log.failures, "mapping the atoms: " + failure,
                        click.describe(request.mapping.tiles, int(method)));
        return;
      }
    }
    const auto& atoms = method == MappingMethod::Displacement ? result.mapped : with_atoms.mapped;
    tally.worst_bond.offer(add_bond_changes(click, atoms, tallied), name);
  }
  catch (const std::exception& e)
  {
    MessageLog::add(log.failures, "measuring the mapped case: " + error_text(e),
                    click.describe(request.mapping.tiles, int(method)));
  }
}

/// Counts a case's time; for polynomial and instancing also the same map again with its disk
/// cached (the baseline: the mapping alone, without growing and parameterizing the disk).
void add_time(const Click& click, const mesolens::MapRequest& request, double seconds, bool mapped,
              Tally& tally)
{
  const MappingMethod method = request.mapping.method;
  MethodTally& tallied = tally.methods[std::size_t(method)];
  tallied.seconds.push_back(seconds);
  if (method == MappingMethod::Displacement)
  {
    return;
  }
  if (seconds > tally.slowest)
  {
    tally.slowest = seconds;
    tally.slowest_case = click.name(request.mapping.tiles, int(method));
  }
  if (mapped)
  {
    mesolens::MapResult cached;
    tallied.cached_seconds.push_back(
      seconds_of([&] { try_map(click, request, mesolens_test::two_threads(), cached); }));
  }
}

/// One case: timed on 2 threads with nothing cached, again on 1 thread with nothing cached
/// (compared bitwise), then measured.
void run_case(const Click& click, int tiles, int method, Tally& tally, MessageLog& log)
{
  mesolens::MapRequest request;
  request.mapping.method = MappingMethod(method);
  request.mapping.tiles = tiles;
  request.mapping.scale = micron_per_angstrom;
  request.mapping.map_atoms = false; // as the renderer maps; displacement always maps atoms
  mesolens::MapResult result, again;
  std::string failure;
  click.mapper.forget_charts();
  const double seconds =
    seconds_of([&] { failure = try_map(click, request, mesolens_test::two_threads(), result); });
  click.mapper.forget_charts();
  const std::string failure_again = try_map(click, request, {}, again);
  add_time(click, request, seconds, failure.empty(), tally);

  const std::string describe = click.describe(tiles, method);
  ++tally.cases;
  ++tally.asked_by_tiles[tiles][1];
  ++tally.compared;
  if (failure != failure_again || (failure.empty() && !same_output(result, again)))
  {
    ++tally.mismatches;
    MessageLog::add(log.failures, "different output on 1 and 2 threads", describe);
  }
  if (!failure.empty())
  {
    MessageLog::add(log.failures, failure, describe);
    return;
  }
  ++tally.mapped;
  const bool as_asked = result.tiles_mapped == tiles && !result.cut_to_disk;
  tally.asked += as_asked ? 1 : 0;
  tally.asked_by_tiles[tiles][0] += as_asked ? 1 : 0;
  tally.cut += result.cut_to_disk ? 1 : 0;
  if (!result.note.empty())
  {
    MessageLog::add(log.notes, result.note, describe);
  }
  again = {};
  measure_quality(click, request, result, tally, log);
}

// ---------------------------------------------------------------------------------------------
// Printing

std::string milliseconds(const std::vector<double>& seconds)
{
  if (seconds.empty())
  {
    return "-";
  }
  char text[96];
  std::snprintf(text, sizeof text, "median %.1f ms, max %.1f ms", 1e3 * percentile(seconds, 0.5),
                1e3 * percentile(seconds, 1.0));
  return text;
}

/// Both lines of a tally: mapping, time, mid-sheet and determinism; bonds and polynomial fits.
void print_tally(const std::string& label, const Tally& tally, std::size_t atoms_per_tile)
{
  std::string by_tiles;
  for (const auto& [k, counts] : tally.asked_by_tiles)
  {
    by_tiles += (by_tiles.empty() ? "" : ", ") + std::to_string(k) + ": " +
      std::to_string(counts[0]) + "/" + std::to_string(counts[1]);
  }
  std::vector<double> gpu_path = tally.methods[1].seconds, cached = tally.methods[1].cached_seconds;
  gpu_path.insert(gpu_path.end(), tally.methods[2].seconds.begin(), tally.methods[2].seconds.end());
  cached.insert(cached.end(), tally.methods[2].cached_seconds.begin(),
                tally.methods[2].cached_seconds.end());
  const auto& displaced = tally.methods[0];
  const auto& fitted = tally.methods[2];
  std::printf(
    "BENCH robustness %s | %zu cases: mapped something %zu = %.1f %% (goal 100 %%), the asked k "
    "%zu = %.1f %% (by k: %s), one tile cut to a disk %zu | map, nothing cached, 2 threads: "
    "polynomial %s, instancing %s (no atoms; both: median %.1f ms = %.2f x the 100 ms goal = "
    "%.1f x the same maps with their disk cached (%.1f ms), max %.0f ms = %.2f x the 1 s goal; "
    "slowest %s); displacement (%s atoms per tile) %s | mid-sheet from the input mesh max: "
    "displacement %.2f nm, polynomial %.2f nm; from the smooth surface: %.3f nm, "
    "%.3f nm | 1 vs 2 threads: %zu mismatches in %zu cases | all took %.0f s\n",
    label.c_str(), tally.cases, tally.mapped, share(tally.mapped, tally.cases), tally.asked,
    share(tally.asked, tally.cases), by_tiles.c_str(), tally.cut,
    milliseconds(tally.methods[2].seconds).c_str(), milliseconds(tally.methods[1].seconds).c_str(),
    1e3 * percentile(gpu_path, 0.5), percentile(gpu_path, 0.5) / goal_median_seconds,
    percentile(gpu_path, 0.5) / percentile(cached, 0.5), 1e3 * percentile(cached, 0.5),
    1e3 * percentile(gpu_path, 1.0), percentile(gpu_path, 1.0) / goal_max_seconds,
    tally.slowest_case.empty() ? "-" : tally.slowest_case.c_str(),
    atoms_per_tile ? std::to_string(atoms_per_tile).c_str() : "each membrane's",
    milliseconds(displaced.seconds).c_str(), nanometres_per_micron * displaced.mid_sheet_from_input,
    nanometres_per_micron * fitted.mid_sheet_from_input,
    nanometres_per_micron * displaced.mid_sheet_from_smooth,
    nanometres_per_micron * fitted.mid_sheet_from_smooth, tally.mismatches, tally.compared,
    tally.wall_seconds);
  std::string bonds;
  for (int m = 0; m < 3; ++m)
  {
    const MethodTally& t = tally.methods[std::size_t(m)];
    char text[160];
    std::snprintf(text, sizeof text, "%s%s %.2e / %.2e / %.2e", m ? "; " : "", method_names[m],
                  percentile(t.bond_sample, 0.5), percentile(t.bond_sample, 0.95), t.bond_max);
    bonds += text;
  }
  std::printf(
    "REPORT robustness-quality %s | |bond length change| median / 95th percentile / "
    "max: %s | polynomial max residual per tile median %.2f Å, max %.2f Å (tiles kept "
    "as polynomials: max %.2f Å); %zu of %zu tiles split into pieces (in %zu of %zu "
    "maps); %zu tiles fell back to displacement | largest |bond length change| %.2e at %s; "
    "largest mid-sheet distance from the input mesh %.2f nm at %s\n",
    label.c_str(), bonds.c_str(), percentile(tally.residuals, 0.5),
    percentile(tally.residuals, 1.0), tally.kept_residual_max, tally.split_tiles,
    tally.polynomial_tiles, tally.split_maps, tally.polynomial_maps, tally.fallback_tiles,
    tally.worst_bond.value, tally.worst_bond.at.empty() ? "-" : tally.worst_bond.at.c_str(),
    nanometres_per_micron * tally.worst_mid_sheet.value,
    tally.worst_mid_sheet.at.empty() ? "-" : tally.worst_mid_sheet.at.c_str());
}

void print_groups(const char* kind, const std::map<std::string, Occurrences>& groups)
{
  std::vector<std::pair<std::string, Occurrences>> sorted(groups.begin(), groups.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second.count > b.second.count; });
  std::size_t total = 0;
  for (const auto& [message, group] : sorted)
  {
    total += group.count;
    std::printf("REPORT robustness-%s %zu x \"%s\" | e.g. %s\n", kind, group.count, message.c_str(),
                group.example.c_str());
  }
  std::printf("REPORT robustness-%s total: %zu in %zu groups\n", kind, total, sorted.size());
}

// ---------------------------------------------------------------------------------------------
// Runs

/// V, F, Euler characteristic, genus, components and boundary of a mesh, one line.
std::string describe_topology(const mesolens::TriangleMesh& mesh, int expected_genus)
{
  const mesolens::MeshReport report = mesolens::mesh_report(mesh.view());
  // chi = sum over components of 2 - 2 g - b.
  const long genus =
    (2 * long(report.components) - report.euler_characteristic - long(report.boundary_loops)) / 2;
  char text[320];
  std::snprintf(text, sizeof text,
                "%zu V / %zu F, Euler characteristic %ld, genus %ld%s, %zu component(s), %zu "
                "boundary loop(s), %s",
                report.vertices, report.triangles, report.euler_characteristic, genus,
                expected_genus < 0 ? ""
                  : genus == expected_genus && report.is_closed_manifold() && report.components == 1
                  ? " (as built)"
                  : " (NOT as built)",
                report.components, report.boundary_loops,
                report.is_closed_manifold() ? "closed manifold"
                  : report.is_manifold()    ? "manifold with boundary"
                                            : "not a manifold");
  return text;
}

/// The mesh from its source; false (printed) when it cannot be read.
bool load_mesh(const MeshSource& source, mesolens::TriangleMesh& mesh, double& seconds)
{
  std::string error;
  seconds = seconds_of([&] {
    if (source.read)
    {
      if (const auto surface = source.read(error))
      {
        mesh = triangle_mesh(surface);
      }
    }
    else
    {
      mesh = source.make();
    }
  });
  if (!error.empty())
  {
    std::printf("REPORT robustness-mesh %s (%s): cannot be read: %s\n", source.name.c_str(),
                source.what.c_str(), error.c_str());
  }
  return error.empty();
}

/// The mapper of a mesh (printed with the mesh); null when MembraneMapper refuses the mesh.
std::unique_ptr<mesolens::MembraneMapper> prepare_mapper(const MeshSource& source,
                                                         const mesolens::TriangleMesh& mesh,
                                                         double load_seconds, MessageLog& log)
{
  std::unique_ptr<mesolens::MembraneMapper> mapper;
  std::string refused;
  const double setup = seconds_of([&] {
    try
    {
      mapper = std::make_unique<mesolens::MembraneMapper>(mesh);
    }
    catch (const std::exception& e)
    {
      refused = error_text(e);
    }
  });
  std::printf(
    "BENCH robustness-mesh %s (%s): %s | read or made in %.2f s, mapper set-up %.2f s%s%s\n",
    source.name.c_str(), source.what.c_str(),
    describe_topology(mesh, source.expected_genus).c_str(), load_seconds, setup,
    refused.empty() ? "" : " | REFUSED by MembraneMapper: ", refused.c_str());
  if (!refused.empty())
  {
    MessageLog::add(log.failures, "mesh refused: " + refused, "mesh=" + source.name);
  }
  return mapper;
}

/// Every case of one mesh with one membrane.
Tally run_clicks(const MeshSource& source, const mesolens::MembraneMapper& mapper,
                 const std::vector<std::int64_t>& vertices, const Membrane& membrane,
                 const Options& options, MessageLog& log)
{
  Tally tally;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t c = 0; c < vertices.size(); ++c)
  {
    const bool bonds = int(c) < options.bond_clicks;
    Click click{ mapper, membrane, source.name, int(c), vertices[c], bonds, {} };
    try
    {
      click.seed = mapper.seed_near(mapper.surface().mesh().point(vertices[c]));
    }
    catch (const std::exception& e)
    {
      MessageLog::add(log.failures, "seed_near: " + error_text(e), click.name(0, 0));
      continue;
    }
    for (const int tiles : options.tiles)
    {
      for (const int method : options.methods)
      {
        run_case(click, tiles, method, tally, log);
      }
    }
  }
  tally.wall_seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tally;
}

/// Every case of one mesh. Returns false when the mesh is required and cannot be read.
bool run_mesh(const MeshSource& source, const std::vector<Membrane>& membranes,
              const Options& options, Tally& total, MessageLog& log)
{
  mesolens::TriangleMesh mesh;
  double load_seconds = 0;
  if (!load_mesh(source, mesh, load_seconds))
  {
    return !source.required;
  }
  const auto mapper = prepare_mapper(source, mesh, load_seconds, log);
  if (!mapper)
  {
    return true;
  }
  int clicks = options.clicks;
  if (source.max_clicks > 0 && source.max_clicks < clicks)
  {
    clicks = source.max_clicks;
    std::printf("REPORT robustness-reduced %s: %d clicks instead of %d (to keep the run short)\n",
                source.name.c_str(), clicks, options.clicks);
  }
  const std::vector<std::int64_t> vertices = farthest_vertices(mesh, clicks);
  mesh = {};
  for (const Membrane& membrane : membranes)
  {
    const Tally tally = run_clicks(source, *mapper, vertices, membrane, options, log);
    print_tally("mesh=" + source.name + " membrane=" + membrane.name, tally, membrane.table.size());
    total.add(tally);
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  const Options options = parse_options(argc, argv);
  std::string tiles;
  for (const int k : options.tiles)
  {
    tiles += (tiles.empty() ? "" : ", ") + std::to_string(k);
  }
  std::printf("BENCH robustness: %d click(s) per mesh (farthest-point samples of its vertices), "
              "tiles %s, %zu method(s), scale %.0e µm/Å; times on 2 threads%s\n",
              options.clicks, tiles.c_str(), options.methods.size(), micron_per_angstrom,
              options.smoke ? " (smoke form)" : "");
  if (options.bond_clicks < options.clicks)
  {
    std::printf("REPORT robustness-reduced bond lengths (which need every atom mapped) on the "
                "first %d clicks of each mesh only, to keep the run near 30 min on 2 cores\n",
                options.bond_clicks);
  }
  std::vector<Membrane> membranes;
  if (!read_membranes(options, membranes))
  {
    return 1;
  }
  Tally total;
  MessageLog log;
  for (const MeshSource& source : mesh_sources(options))
  {
    if (!run_mesh(source, membranes, options, total, log))
    {
      return 1;
    }
  }
  print_tally("mesh=all membrane=all", total, 0);
  print_groups("failure", log.failures);
  print_groups("note", log.notes);
  return 0;
}
