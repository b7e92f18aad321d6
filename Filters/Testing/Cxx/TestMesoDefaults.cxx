// SPDX-License-Identifier: GPL-3.0-or-later
// Every filter parameter that a Core parameter struct holds starts at that struct's default
// (Core is the one place defaults are written), and the filter's setter, which may clamp,
// keeps it.
#include "vtkMesoGeodesicDisk.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoMolecularSurface.h"
#include "vtkMesoRibbons.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoAtomProperties.h"
#include "vtkMesoSurfaceArea.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/cutaway/structured_cutaway.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/protein/dssp.h"
#include "mesolens/protein/ribbon_geometry.h"
#include "mesolens/molecules/elements.h"
#include "mesolens/surface/molecular_surface.h"

#include <vtkNew.h>

#include <gtest/gtest.h>

// filter->Get<name>() equals `core_default` (in the getter's type), and filter->Set<name>() of
// it keeps it: a default outside the setter's clamp range fails too.
#define EXPECT_CORE_DEFAULT(filter, name, core_default)                                            \
  do                                                                                               \
  {                                                                                                \
    using Value = decltype((filter)->Get##name());                                                 \
    const Value initial = (filter)->Get##name();                                                   \
    EXPECT_EQ(initial, static_cast<Value>(core_default)) << #name " is not Core's default";        \
    (filter)->Set##name(initial);                                                                  \
    EXPECT_EQ((filter)->Get##name(), initial) << "Set" #name " clamps its default away";           \
  } while (false)

TEST(MesoDefaults, MembraneMapping)
{
  vtkNew<vtkMesoMembraneMapping> filter;
  const mesolens::MapRequest defaults;
  EXPECT_CORE_DEFAULT(filter, MappingMethod, defaults.mapping.method);
  EXPECT_CORE_DEFAULT(filter, Tiles, defaults.mapping.tiles);
  EXPECT_CORE_DEFAULT(filter, MembraneToMeshScale, defaults.mapping.scale);
  EXPECT_CORE_DEFAULT(filter, LayerHalfThickness, defaults.mapping.layer_half_thickness);
  EXPECT_CORE_DEFAULT(filter, PolynomialSamples, defaults.mapping.samples);
  EXPECT_CORE_DEFAULT(filter, MaximumPolynomialResidual, defaults.mapping.max_polynomial_residual);
  EXPECT_CORE_DEFAULT(filter, OutputAtoms, defaults.mapping.map_atoms);
  EXPECT_CORE_DEFAULT(filter, RadiusFactor, defaults.radius_factor);
  EXPECT_CORE_DEFAULT(filter, MaximumStretch, defaults.max_stretch);
  EXPECT_CORE_DEFAULT(filter, MinimumDiskTriangles, defaults.min_disk_triangles);
  EXPECT_CORE_DEFAULT(filter, MaximumDiskTriangles, defaults.max_disk_triangles);
  EXPECT_CORE_DEFAULT(filter, MapWhatFits, defaults.fit_what_fits);
}

TEST(MesoDefaults, GeodesicDisk)
{
  vtkNew<vtkMesoGeodesicDisk> filter;
  const mesolens::GeodesicDiskParams defaults;
  EXPECT_CORE_DEFAULT(filter, MinimumTriangles, defaults.min_triangles);
  EXPECT_CORE_DEFAULT(filter, MaximumTriangles, defaults.max_triangles);
}

TEST(MesoDefaults, MolecularSurface)
{
  vtkNew<vtkMesoMolecularSurface> filter;
  const mesolens::MolecularSurfaceParams defaults;
  EXPECT_CORE_DEFAULT(filter, SurfaceType, defaults.kind);
  EXPECT_CORE_DEFAULT(filter, ProbeRadius, defaults.probe_radius);
  EXPECT_CORE_DEFAULT(filter, Tolerance, defaults.tolerance);
  EXPECT_CORE_DEFAULT(filter, ComputeExactFigures, defaults.exact_figures);
  EXPECT_CORE_DEFAULT(filter, KeepCavities, defaults.keep_cavities);
  EXPECT_CORE_DEFAULT(filter, BeadRadius, mesolens::bead_radius);
  // The surface types are Core's kinds.
  EXPECT_EQ(vtkMesoMolecularSurface::SOLVENT_EXCLUDED, int(mesolens::SurfaceKind::SolventExcluded));
  EXPECT_EQ(vtkMesoMolecularSurface::SOLVENT_ACCESSIBLE,
            int(mesolens::SurfaceKind::SolventAccessible));
  EXPECT_EQ(vtkMesoMolecularSurface::VAN_DER_WAALS, int(mesolens::SurfaceKind::VanDerWaals));
}

TEST(MesoDefaults, SurfaceArea)
{
  vtkNew<vtkMesoSurfaceArea> filter;
  EXPECT_CORE_DEFAULT(filter, ProbeRadius, mesolens::MolecularSurfaceParams().probe_radius);
  EXPECT_CORE_DEFAULT(filter, BeadRadius, mesolens::bead_radius);
}

TEST(MesoDefaults, AtomProperties)
{
  vtkNew<vtkMesoAtomProperties> filter;
  EXPECT_CORE_DEFAULT(filter, BeadRadius, mesolens::bead_radius);
}

TEST(MesoDefaults, SecondaryStructure)
{
  vtkNew<vtkMesoSecondaryStructure> filter;
  const mesolens::DsspParams defaults;
  EXPECT_CORE_DEFAULT(filter, PiHelixPriority, defaults.pi_helix_priority);
  EXPECT_CORE_DEFAULT(filter, PolyprolineStretch, defaults.polyproline_stretch);
  EXPECT_CORE_DEFAULT(filter, Bulges, defaults.bulges);
  EXPECT_CORE_DEFAULT(filter, UseFileHydrogens, defaults.file_hydrogens);
}

TEST(MesoDefaults, Ribbons)
{
  vtkNew<vtkMesoRibbons> filter;
  const mesolens::RibbonParams defaults;
  EXPECT_CORE_DEFAULT(filter, Subdivisions, defaults.subdivisions);
  EXPECT_CORE_DEFAULT(filter, TubeSides, defaults.tube_sides);
  EXPECT_CORE_DEFAULT(filter, HelixAsCylinder, defaults.helix_as_cylinder);
  EXPECT_CORE_DEFAULT(filter, HelixWidth, defaults.helix_width);
  EXPECT_CORE_DEFAULT(filter, StrandWidth, defaults.strand_width);
  EXPECT_CORE_DEFAULT(filter, RibbonThickness, defaults.ribbon_thickness);
  EXPECT_CORE_DEFAULT(filter, CoilRadius, defaults.coil_radius);
  EXPECT_CORE_DEFAULT(filter, NucleicRadius, defaults.nucleic_radius);
  EXPECT_CORE_DEFAULT(filter, CylinderRadius, defaults.cylinder_radius);
  EXPECT_CORE_DEFAULT(filter, ArrowWidthFactor, defaults.arrow_width_factor);
}

TEST(MesoDefaults, StructuredCutaway)
{
  vtkNew<vtkMesoStructuredCutaway> filter;
  const mesolens::CutawayParams cut;
  EXPECT_CORE_DEFAULT(filter, K, cut.k);
  EXPECT_CORE_DEFAULT(filter, FractionHidden, cut.fraction_hidden);
  EXPECT_CORE_DEFAULT(filter, Inverted, cut.inverted);
  EXPECT_CORE_DEFAULT(filter, RandomOrder, cut.random);
  EXPECT_CORE_DEFAULT(filter, ProbabilisticOrder, cut.probabilistic);
  EXPECT_CORE_DEFAULT(filter, Seed, cut.seed);
  const mesolens::StructureMeshParams structure;
  EXPECT_CORE_DEFAULT(filter, StructureVertices, structure.vertices);
  EXPECT_CORE_DEFAULT(filter, StructureMidSurfaceRadius, structure.mid_surface_radius);
}

namespace {
/// The options every atom reader shares (vtkMesoAtomReader) start at Core's defaults. A float
/// default compares as a float: the reader's double holds the float's decimal.
void ExpectAtomReaderDefaults(vtkMesoAtomReader* reader)
{
  const mesolens::StructureReadParams defaults;
  EXPECT_CORE_DEFAULT(reader, RemoveWaters, defaults.remove_waters);
  EXPECT_CORE_DEFAULT(reader, PerceiveBonds, defaults.perceive_bonds);
  EXPECT_CORE_DEFAULT(reader, ForceCoarseGrained, defaults.force_coarse_grained);
  EXPECT_EQ(static_cast<float>(reader->GetBondTolerance()), defaults.bonds.tolerance);
  EXPECT_EQ(static_cast<float>(reader->GetCoarseGrainedBeadCutoff()), defaults.bonds.bead_cutoff);
  const double tolerance = reader->GetBondTolerance();
  const double cutoff = reader->GetCoarseGrainedBeadCutoff();
  reader->SetBondTolerance(tolerance);
  reader->SetCoarseGrainedBeadCutoff(cutoff);
  EXPECT_EQ(reader->GetBondTolerance(), tolerance);
  EXPECT_EQ(reader->GetCoarseGrainedBeadCutoff(), cutoff);
}
} // namespace

TEST(MesoDefaults, StructureReader)
{
  vtkNew<vtkMesoStructureReader> reader;
  ExpectAtomReaderDefaults(reader);
  const mesolens::StructureReadParams defaults;
  EXPECT_CORE_DEFAULT(reader, KeepAllAlternateLocations,
                      defaults.alt_locs == mesolens::AltLocPolicy::KeepAll);
  EXPECT_CORE_DEFAULT(reader, RemoveHydrogens, defaults.remove_hydrogens);
}

TEST(MesoDefaults, TrajectoryReader)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  ExpectAtomReaderDefaults(reader);
}
