// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoXMLPolyDataReader.h"

#include <vtkObjectFactory.h>
#include <vtkXMLDataParser.h>

#include <expat.h>

namespace {
/// vtkXMLDataParser whose expat parser parses each chunk at once.
class ImmediateXMLDataParser : public vtkXMLDataParser
{
public:
  static ImmediateXMLDataParser* New();
  vtkTypeMacro(ImmediateXMLDataParser, vtkXMLDataParser);

protected:
  int CreateParser() override
  {
    if (!this->Superclass::CreateParser())
    {
      return 0;
    }
#ifdef MESOLENS_EXPAT_HAS_REPARSE_DEFERRAL
    XML_SetReparseDeferralEnabled(static_cast<XML_Parser>(this->Parser), XML_FALSE);
#endif
    return 1;
  }
};
vtkStandardNewMacro(ImmediateXMLDataParser);
} // namespace

vtkStandardNewMacro(vtkMesoXMLPolyDataReader);

void vtkMesoXMLPolyDataReader::CreateXMLParser()
{
  if (this->XMLParser)
  {
    this->DestroyXMLParser();
  }
  this->XMLParser = ImmediateXMLDataParser::New();
}
