// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: PLY meshes (mesolens::read_ply_bytes). Every input must give a mesh or a
// mesolens::Error; anything else (a crash, a sanitizer report, a hang, a huge allocation) is a
// defect. Run by scripts/fuzz.sh.
#include "mesolens/common/errors.h"
#include "mesolens/io/ply_file.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    const mesolens::MeshFileContents mesh =
      mesolens::read_ply_bytes(std::string(reinterpret_cast<const char*>(data), size), "input");
    // What the reader promises: indices within the vertices, 3 coordinates per vertex.
    const std::size_t vertices = mesh.soup.points.size() / 3;
    for (const auto& polygon : mesh.soup.polygons)
    {
      for (const std::int64_t index : polygon)
      {
        if (index < 0 || std::size_t(index) >= vertices)
        {
          __builtin_trap();
        }
      }
    }
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
