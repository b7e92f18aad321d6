// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoMeshReader
 * @brief   Reads a cell-component surface mesh (.obj, .ply, .stl, .vtp, .off) as triangles.
 *
 * STL and VTP go through VTK's own readers (vtkSTLReader, vtkXMLPolyDataReader), their declared
 * counts checked before (MaximumElements) and their output after (faces naming points the file
 * lacks, non-finite coordinates); OBJ, OFF and PLY (ascii and binary) through MesoLens' own
 * strict readers (mesolens::read_obj, read_off, read_ply: VTK's read garbage numbers as 0, pass
 * on faces past the vertices and crash on PLY files whose header lies; CGAL's OFF scanner takes
 * negative indices), with the vertex normals as `Normals`
 * when the file has them. Meshes with defects (holes, non-manifold or inconsistently oriented
 * faces, degenerate triangles) are read as they are and vtkMesoMeshReport can describe them.
 * Polygons with more than three vertices are split into triangles; vertices, lines and strips
 * are dropped. Points with identical coordinates are merged (writers repeat a vertex per face
 * corner), so the output has the file's topology; the point attributes of the first copy are
 * kept. Coordinates are in the file's own unit (the mitochondrion meshes of the test data are in
 * µm).
 *
 * A missing, empty or unreadable file, or one without any polygon, gives a vtkErrorMacro
 * naming the file, an empty output and a failed update.
 */
#ifndef vtkMesoMeshReader_h
#define vtkMesoMeshReader_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class MESOLENSFILTERS_EXPORT vtkMesoMeshReader : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoMeshReader* New();
  vtkTypeMacro(vtkMesoMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Path of the mesh file. Default: none.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The most points, and the most cells, an STL or VTP file may declare, [1, 1e9]; default
  /// 2e7. VTK's readers allocate what a header declares before reading: a binary STL whose
  /// triangle count the file cannot hold, or a VTP declaring more than this (compressed data can
  /// hold a billion zeros in a few megabytes), is refused before VTK sees it.
  vtkSetClampMacro(MaximumElements, vtkIdType, 1, 1000000000);
  vtkGetMacro(MaximumElements, vtkIdType);
  ///@}

  /// 1 when the extension is .obj, .ply, .stl, .vtp or .off and the file exists.
  static int CanReadFile(const char* fileName);

protected:
  vtkMesoMeshReader();
  ~vtkMesoMeshReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  vtkIdType MaximumElements = 20000000;

private:
  vtkMesoMeshReader(const vtkMesoMeshReader&) = delete;
  void operator=(const vtkMesoMeshReader&) = delete;

  bool ReadWithVTK(const std::string& extension, vtkPolyData* output);
  /// What is wrong with the counts an STL or VTP file declares (see MaximumElements), or empty.
  std::string DeclaredCountProblem(const std::string& extension) const;
  /// OBJ, OFF and PLY: polygon soups read by Core (mesolens::read_obj, read_off, read_ply).
  bool ReadSoup(const std::string& extension, vtkPolyData* output);
};

#endif
