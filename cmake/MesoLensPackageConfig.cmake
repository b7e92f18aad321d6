# SPDX-License-Identifier: GPL-3.0-or-later
# MesoLensConfig.cmake for find_package(MesoLens): vtk_module_build writes the targets and the
# module properties, but no package configuration file.
include(CMakePackageConfigHelpers)
set(mesolens_config_build_dir "${CMAKE_BINARY_DIR}/${mesolens_cmake_destination}")
configure_package_config_file(cmake/MesoLensConfig.cmake.in
  "${mesolens_config_build_dir}/MesoLensConfig.cmake"
  INSTALL_DESTINATION "${mesolens_cmake_destination}")
write_basic_package_version_file("${mesolens_config_build_dir}/MesoLensConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES
  "${mesolens_config_build_dir}/MesoLensConfig.cmake"
  "${mesolens_config_build_dir}/MesoLensConfigVersion.cmake"
  DESTINATION "${mesolens_cmake_destination}")
