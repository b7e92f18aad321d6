// SPDX-License-Identifier: GPL-3.0-or-later
// Strict image comparison for the render tests:
//
//   mesolens_compare_images IMAGE BASELINE [PIXEL_THRESHOLD=16] [MAX_FRACTION=0.002]
//
// A pixel differs when any channel differs by more than PIXEL_THRESHOLD (0-255); the test
// fails when more than MAX_FRACTION of the pixels differ, when the sizes differ, or when the
// baseline is missing (a missing baseline is a failure, never a pass). No shifts, no averaging:
// VTK's default regression threshold let visibly wrong pictures pass. With
// MESOLENS_UPDATE_BASELINES=1 in the environment, a differing or missing baseline is replaced
// by IMAGE and the test still fails, so a new baseline is always looked at before it is kept.
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace {
bool readable(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  return file.good();
}

void copy_file(const std::string& from, const std::string& to)
{
  std::ifstream in(from, std::ios::binary);
  std::ofstream out(to, std::ios::binary);
  out << in.rdbuf();
}

int fail_and_maybe_update(const std::string& image, const std::string& baseline)
{
  const char* update = std::getenv("MESOLENS_UPDATE_BASELINES");
  if (update && std::string(update) == "1")
  {
    copy_file(image, baseline);
    std::cerr << "baseline " << baseline << " was replaced by " << image
              << "; look at it, then run the test again\n";
  }
  return 1;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: mesolens_compare_images IMAGE BASELINE [PIXEL_THRESHOLD] [MAX_FRACTION]\n";
    return 2;
  }
  const std::string image_path = argv[1];
  const std::string baseline_path = argv[2];
  const int pixel_threshold = argc > 3 ? std::atoi(argv[3]) : 16;
  const double max_fraction = argc > 4 ? std::atof(argv[4]) : 0.002;
  if (!readable(image_path))
  {
    std::cerr << "FAIL: the test image " << image_path << " was not written\n";
    return 1;
  }
  if (!readable(baseline_path))
  {
    std::cerr << "FAIL: no baseline " << baseline_path
              << " (MESOLENS_UPDATE_BASELINES=1 creates it)\n";
    return fail_and_maybe_update(image_path, baseline_path);
  }
  vtkNew<vtkPNGReader> image_reader;
  image_reader->SetFileName(image_path.c_str());
  image_reader->Update();
  vtkNew<vtkPNGReader> baseline_reader;
  baseline_reader->SetFileName(baseline_path.c_str());
  baseline_reader->Update();
  vtkImageData* image = image_reader->GetOutput();
  vtkImageData* baseline = baseline_reader->GetOutput();
  int a[3];
  int b[3];
  image->GetDimensions(a);
  baseline->GetDimensions(b);
  const int channels = image->GetNumberOfScalarComponents();
  if (a[0] != b[0] || a[1] != b[1] || channels != baseline->GetNumberOfScalarComponents())
  {
    std::cerr << "FAIL: image is " << a[0] << "x" << a[1] << "x" << channels << ", baseline "
              << b[0] << "x" << b[1] << "x" << baseline->GetNumberOfScalarComponents() << "\n";
    return fail_and_maybe_update(image_path, baseline_path);
  }
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  const auto* q = static_cast<const unsigned char*>(baseline->GetScalarPointer());
  const long pixels = long(a[0]) * long(a[1]);
  long differing = 0;
  int largest = 0;
  for (long i = 0; i < pixels; ++i)
  {
    bool differs = false;
    for (int c = 0; c < channels; ++c)
    {
      const int d = std::abs(int(p[i * channels + c]) - int(q[i * channels + c]));
      largest = d > largest ? d : largest;
      differs = differs || d > pixel_threshold;
    }
    differing += differs ? 1 : 0;
  }
  const double fraction = double(differing) / double(pixels);
  std::cout << "differing pixels: " << differing << " of " << pixels << " (" << 100.0 * fraction
            << " %, allowed " << 100.0 * max_fraction << " %), largest channel difference "
            << largest << "\n";
  if (fraction > max_fraction)
  {
    std::cerr << "FAIL: " << image_path << " differs from " << baseline_path << "\n";
    return fail_and_maybe_update(image_path, baseline_path);
  }
  return 0;
}
