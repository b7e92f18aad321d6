// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoXMLPolyDataReader
 * @brief   vtkXMLPolyDataReader that reads appended data with expat 2.6's reparse deferral
 *          (private to MesoLensFilters; not installed, not wrapped).
 *
 * Expat 2.6 (and Debian 12's libexpat1 from 2.5.0-1+deb12u2 on, which backports it) defers
 * parsing a token that a chunk cut until more input arrives. VTK 9.2's XML parser feeds the
 * file in chunks and stops at <AppendedData>; with deferral the element events come late and
 * every .vtp with appended data fails ("junk after document element"; VTK issue 19258, fixed
 * in VTK 9.3). This reader's parser turns the deferral off, as VTK 9.3 does.
 */
#ifndef vtkMesoXMLPolyDataReader_h
#define vtkMesoXMLPolyDataReader_h

#include <vtkXMLPolyDataReader.h>

class vtkMesoXMLPolyDataReader : public vtkXMLPolyDataReader
{
public:
  static vtkMesoXMLPolyDataReader* New();
  vtkTypeMacro(vtkMesoXMLPolyDataReader, vtkXMLPolyDataReader);

protected:
  vtkMesoXMLPolyDataReader() = default;
  ~vtkMesoXMLPolyDataReader() override = default;

  void CreateXMLParser() override;

private:
  vtkMesoXMLPolyDataReader(const vtkMesoXMLPolyDataReader&) = delete;
  void operator=(const vtkMesoXMLPolyDataReader&) = delete;
};

#endif
