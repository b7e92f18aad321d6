# SPDX-License-Identifier: GPL-3.0-or-later
# Third-party libraries used by Core (never exposed through public VTK headers).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(ZLIB REQUIRED)
find_package(CGAL REQUIRED)
# CONFIG: CGAL puts its own FindOpenMesh.cmake on the module path, which misses Debian's layout.
find_package(OpenMesh REQUIRED CONFIG)
find_path(GEMMI_INCLUDE_DIR gemmi/mmread.hpp)
find_path(PEGTL_INCLUDE_DIR tao/pegtl.hpp)
if (NOT GEMMI_INCLUDE_DIR OR NOT PEGTL_INCLUDE_DIR)
  message(FATAL_ERROR "gemmi headers not found: install gemmi-dev and tao-pegtl-dev")
endif ()

# GROMACS 2022 ships a pkg-config file whose Cflags carry -fopenmp, which MesoLens does not
# need: use only its include and library paths.
find_package(PkgConfig REQUIRED)
pkg_check_modules(GROMACS REQUIRED libgromacs)
find_library(GROMACS_LIBRARY NAMES gromacs HINTS ${GROMACS_LIBRARY_DIRS} REQUIRED)
add_library(mesolens_gromacs INTERFACE)
target_include_directories(mesolens_gromacs INTERFACE ${GROMACS_INCLUDE_DIRS})
target_compile_definitions(mesolens_gromacs INTERFACE GMX_DOUBLE=0)
target_link_libraries(mesolens_gromacs INTERFACE "${GROMACS_LIBRARY}")

# Core declares a few functions that libgromacs exports without installing their headers
# (Core/io/detail/gromacs_support.h); make sure this GROMACS still has them.
include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_INCLUDES ${GROMACS_INCLUDE_DIRS})
set(CMAKE_REQUIRED_LIBRARIES "${GROMACS_LIBRARY}")
check_cxx_source_compiles([[
#include <cstdint>
#include <string>
struct t_fileio;
std::int64_t gmx_fio_ftell(t_fileio*);
int gmx_fio_seek(t_fileio*, std::int64_t);
void gmx_set_error_handler(void (*)(const char*, const std::string&, const char*, int));
int main() { gmx_set_error_handler(nullptr); return gmx_fio_seek(nullptr, gmx_fio_ftell(nullptr)) != 0 ? 0 : 1; }
]] MESOLENS_GROMACS_HAS_FILE_API)
unset(CMAKE_REQUIRED_INCLUDES)
unset(CMAKE_REQUIRED_LIBRARIES)
if (NOT MESOLENS_GROMACS_HAS_FILE_API)
  message(FATAL_ERROR "libgromacs lacks gmx_fio_seek/gmx_fio_ftell/gmx_set_error_handler; "
    "MesoLens needs GROMACS 2022 (Debian 12's libgromacs-dev)")
endif ()
