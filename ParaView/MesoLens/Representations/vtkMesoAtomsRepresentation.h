// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoAtomsRepresentation
 * @brief   ParaView's "MesoLens Atoms" representation: atoms and bonds drawn by
 *          vtkMesoAtomMapper (ray-cast sphere and cylinder impostors with true depth).
 *
 * Chosen in the render view's representation list ("MesoLens Atoms") for any output of a
 * MesoLens reader or filter: atoms are the points (the `AtomicNumber` point array gives radii and
 * element colours), bonds the 2-point lines. Other datasets (ParaView's Threshold or Extract
 * Selection of atoms) are drawn as their points and 2-point lines; the blocks of a composite
 * dataset are appended first. Style, RadiusScale, BallScale, BondRadius,
 * OcclusionCulling and VisibilityArrayName are the mapper's (see vtkMesoAtomMapper).
 *
 * Colours: with no colour array (ParaView's "Solid Color") atoms take their element colours
 * times the diffuse colour (white by default); a point array chosen to colour by goes through
 * the view's lookup table. Cell arrays are not drawn (atoms are points).
 *
 * In ParaView's render view it works with the view's ambient occlusion (UseSSAO), translucency
 * (Opacity), picking and selection (atom i is point i and vertex cell i, as in the input), and
 * with IceT's compositing on many MPI ranks, since every fragment has the sphere's true depth.
 * The bounds given to the view include the atoms' radii. Translucent atoms on several ranks are
 * composited without sorting across ranks.
 */
#ifndef vtkMesoAtomsRepresentation_h
#define vtkMesoAtomsRepresentation_h

#include "MesoLensParaViewRepresentationsModule.h"
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h"

class vtkActor;
class vtkMesoAtomMapper;
class vtkPolyData;
class vtkScalarsToColors;

class MESOLENSPARAVIEWREPRESENTATIONS_EXPORT vtkMesoAtomsRepresentation
  : public vtkPVDataRepresentation
{
public:
  static vtkMesoAtomsRepresentation* New();
  vtkTypeMacro(vtkMesoAtomsRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request, vtkInformation* inInfo,
                         vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  /// The mapper's properties (vtkMesoAtomMapper documents units, ranges and defaults).
  void SetStyle(int style);
  void SetRadiusScale(double scale);
  void SetBallScale(double scale);
  void SetBondRadius(double radius);
  void SetOcclusionCulling(bool cull);
  void SetVisibilityArrayName(const char* name);

  /// The lookup table for the colour array (ParaView's ColorArrayName, set through
  /// SetInputArrayToProcess); its own range is used.
  void SetLookupTable(vtkScalarsToColors* table);

  /// The actor's surface properties, as in ParaView's Surface representation.
  void SetOpacity(double opacity);
  void SetAmbient(double ambient);
  void SetDiffuse(double diffuse);
  void SetSpecular(double specular);
  void SetSpecularPower(double power);
  void SetAmbientColor(double r, double g, double b);
  void SetDiffuseColor(double r, double g, double b);
  void SetSpecularColor(double r, double g, double b);
  void SetPickable(int pickable);
  void SetPosition(double x, double y, double z);
  void SetOrientation(double x, double y, double z);
  void SetScale(double x, double y, double z);
  void SetOrigin(double x, double y, double z);

  /// The mapper, for tests and for settings not exposed above.
  vtkMesoAtomMapper* GetMapper() const
  {
    return this->Mapper;
  }

protected:
  vtkMesoAtomsRepresentation();
  ~vtkMesoAtomsRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputs,
                  vtkInformationVector* outputs) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  vtkMesoAtomsRepresentation(const vtkMesoAtomsRepresentation&) = delete;
  void operator=(const vtkMesoAtomsRepresentation&) = delete;

  /// The colour array chosen through SetInputArrayToProcess, given to the mapper.
  void UpdateColoring();
  /// Padded by the largest radius: the view's camera reset and IceT's compositing see the
  /// whole spheres.
  void ComputeBounds(double bounds[6]);

  vtkSmartPointer<vtkPolyData> Atoms; // what this rank draws
  vtkMesoAtomMapper* Mapper;
  vtkMesoAtomMapper* BoundsMapper; // the bounds of this rank's atoms, with the same style
  vtkActor* Actor;
};

#endif
