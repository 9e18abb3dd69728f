# BONDED_LATTICE compiled into LAMMPS itself (built-in mode), for static builds and
# for LAMMPS built without the PLUGIN package.  Give this file to LAMMPS' own CMake
# build; nothing in the LAMMPS source tree is changed:
#
#   cmake -S lammps/cmake -B build-lammps \
#         -DCMAKE_PROJECT_lammps_INCLUDE=/path/to/bonded-lattice/cmake/bonded_lattice_builtin.cmake \
#         -DPKG_BPM=on ...            (any other LAMMPS options)
#   cmake --build build-lammps
#
# CMake reads this file right after LAMMPS' project(lammps) line, and the file then
# defers its work to the end of LAMMPS' cmake/CMakeLists.txt, when the `lammps`
# target and the style lists exist.  Appending `include(<this file>)` to LAMMPS'
# cmake/CMakeLists.txt (as DeePMD-kit's built-in mode does) works as well.
#
# What it does: adds src/BONDED_LATTICE/*.cpp (not the plugin's registration file),
# and with LAMMPS' OPENMP package src/BONDED_LATTICE/OPENMP/*.cpp, to the `lammps` target, compiled with the plugin's options; writes
# bonded_lattice_config.h (versions, build mode, and the LAMMPS interface switches
# found by compiling against this LAMMPS: cmake/BondedLatticeApi.cmake); registers
# the styles and regenerates LAMMPS' style headers, so that `pair_style
# lattice/bond` and the rest exist without `plugin load`.  The command
# `bonded_lattice` reports the version and "compiled into LAMMPS".
#
# The package's headers are copied into <build>/bonded_lattice and that folder
# (not the checkout) is on LAMMPS' include path: LAMMPS' own files include them
# through the style headers, and a build folder reused with another checkout of
# the package then recompiles only the package's files, not all of LAMMPS.
# (no cmake_minimum_required here: it would change LAMMPS' own policy settings)
if(CMAKE_VERSION VERSION_LESS 3.19)
  message(FATAL_ERROR "bonded_lattice_builtin.cmake needs CMake 3.19 or newer "
                      "(cmake_language(DEFER)); this is CMake ${CMAKE_VERSION}")
endif()
if(NOT PROJECT_NAME STREQUAL "lammps")
  # CMAKE_PROJECT_INCLUDE (for every project) may bring us into other projects
  return()
endif()
get_property(_bonded_lattice_done GLOBAL PROPERTY BONDED_LATTICE_BUILTIN_INCLUDED)
if(_bonded_lattice_done)
  return()
endif()
set_property(GLOBAL PROPERTY BONDED_LATTICE_BUILTIN_INCLUDED TRUE)
get_filename_component(BONDED_LATTICE_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

# the package's headers (and with LAMMPS' OPENMP package those of OPENMP/ in
# <inc>/OPENMP), copied: configure_file rewrites a copy only when it changed, and
# re-runs CMake when a header changes
function(_bonded_lattice_copy_headers src inc)
  file(GLOB headers CONFIGURE_DEPENDS "${src}/*.h")
  file(GLOB stale "${inc}/*.h")
  list(REMOVE_ITEM stale "${inc}/bonded_lattice_config.h")
  foreach(header IN LISTS headers)
    get_filename_component(name "${header}" NAME)
    configure_file("${header}" "${inc}/${name}" COPYONLY)
    list(REMOVE_ITEM stale "${inc}/${name}")
  endforeach()
  if(stale)
    file(REMOVE ${stale})    # headers removed from the package
  endif()
endfunction()

function(_bonded_lattice_headers src inc)
  _bonded_lattice_copy_headers("${src}" "${inc}")
  if(PKG_OPENMP)
    _bonded_lattice_copy_headers("${src}/OPENMP" "${inc}/OPENMP")
  else()
    file(REMOVE_RECURSE "${inc}/OPENMP")
  endif()
endfunction()

# register the package's styles with LAMMPS (and its /omp styles with OPENMP)
macro(_bonded_lattice_register inc)
  RegisterStyles("${inc}")
  if(PKG_OPENMP)
    RegisterStyles("${inc}/OPENMP")
  endif()
endmacro()

function(_bonded_lattice_builtin)
  if(NOT TARGET lammps OR NOT COMMAND RegisterStyles OR NOT LAMMPS_STYLE_HEADERS_DIR)
    message(FATAL_ERROR "bonded_lattice_builtin.cmake: give it to LAMMPS' own CMake build "
                        "(-DCMAKE_PROJECT_lammps_INCLUDE=<this file> with -S <lammps>/cmake); "
                        "it found no `lammps` target or style header functions")
  endif()
  set(src "${BONDED_LATTICE_ROOT}/src/BONDED_LATTICE")
  set(inc "${CMAKE_BINARY_DIR}/bonded_lattice")

  # the package version: the one of the plugin build (project() in CMakeLists.txt)
  file(STRINGS "${BONDED_LATTICE_ROOT}/CMakeLists.txt" project_line
       REGEX "^project\\(bonded_lattice VERSION [0-9.]+")
  if(NOT project_line MATCHES "VERSION ([0-9.]+)")
    message(FATAL_ERROR "bonded_lattice_builtin.cmake: no `project(bonded_lattice VERSION ...)` "
                        "line in ${BONDED_LATTICE_ROOT}/CMakeLists.txt")
  endif()
  set(BONDED_LATTICE_VERSION "${CMAKE_MATCH_1}")
  set(BONDED_LATTICE_LAMMPS_VERSION "${PROJECT_VERSION}")
  set(BONDED_LATTICE_BUILT_IN 1)

  # this LAMMPS' interfaces: compile against its source tree, with its MPI or MPI stubs
  include("${BONDED_LATTICE_ROOT}/cmake/BondedLatticeApi.cmake")
  set(includes "${LAMMPS_SOURCE_DIR}")
  set(libraries)
  if(BUILD_MPI)
    set(libraries MPI::MPI_CXX)
  else()
    list(APPEND includes "${LAMMPS_SOURCE_DIR}/STUBS")
  endif()
  bonded_lattice_check_api(INCLUDES ${includes} DEFINITIONS "-DLAMMPS_${LAMMPS_SIZES}"
                           LIBRARIES ${libraries})
  configure_file("${src}/bonded_lattice_config.h.in" "${inc}/bonded_lattice_config.h" @ONLY)

  file(GLOB sources CONFIGURE_DEPENDS "${src}/*.cpp")
  list(REMOVE_ITEM sources "${src}/bonded_lattice_plugin.cpp")    # `plugin load` only
  target_include_directories(lammps PRIVATE "${inc}")
  if(PKG_OPENMP)
    # pair_style lattice/bond/omp, fix lattice/nve/omp: LAMMPS' OPENMP conventions
    file(GLOB omp_sources CONFIGURE_DEPENDS "${src}/OPENMP/*.cpp")
    list(APPEND sources ${omp_sources})
    target_include_directories(lammps PRIVATE "${inc}/OPENMP")
    message(STATUS "BONDED_LATTICE: with the /omp styles (LAMMPS' OPENMP package)")
  endif()
  target_sources(lammps PRIVATE ${sources})
  # the plugin's options, on the package's files only: sqrt() without errno, and no
  # fused multiply-add contraction (the same bits as the plugin)
  set_source_files_properties(${sources} PROPERTIES
    COMPILE_OPTIONS "-fno-math-errno;-ffp-contract=off")
  # LatticeSparseCholesky::set_threads: std::thread
  find_package(Threads REQUIRED)
  target_link_libraries(lammps PRIVATE Threads::Threads)

  # the styles were registered before LAMMPS wrote its style headers (below);
  # included at the end of LAMMPS' CMakeLists.txt, they are registered now and the
  # style headers written again
  file(READ "${LAMMPS_STYLE_HEADERS_DIR}/style_pair.h" style_pair)
  if(NOT style_pair MATCHES "pair_lattice_bond.h")
    _bonded_lattice_register("${inc}")
    GenerateStyleHeaders("${LAMMPS_STYLE_HEADERS_DIR}")
  endif()

  # list BONDED_LATTICE among the installed packages (`lmp -h`, `info config`,
  # lammps.has_package() in Python): LAMMPS wrote lmpinstalledpkgs.h from its own
  # package list; rewrite it with ours added, in sorted order
  set(pkgs_h "${LAMMPS_STYLE_HEADERS_DIR}/lmpinstalledpkgs.h")
  file(STRINGS "${pkgs_h}" names REGEX "^  \"[A-Z0-9_-]+\",$")
  list(TRANSFORM names REPLACE "^  \"([A-Z0-9_-]+)\",$" "\\1")
  list(APPEND names BONDED_LATTICE)
  list(REMOVE_DUPLICATES names)
  list(SORT names)
  set(text "#ifndef LMP_INSTALLED_PKGS_H\n#define LMP_INSTALLED_PKGS_H\n")
  string(APPEND text "const char * LAMMPS_NS::LAMMPS::installed_packages[] =  {\n")
  foreach(name IN LISTS names)
    string(APPEND text "  \"${name}\",\n")
  endforeach()
  string(APPEND text "  NULL\n};\n#endif\n\n")
  file(WRITE "${pkgs_h}.bonded_lattice.tmp" "${text}")
  execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${pkgs_h}.bonded_lattice.tmp" "${pkgs_h}")
  message(STATUS "BONDED_LATTICE ${BONDED_LATTICE_VERSION}: compiled into LAMMPS "
                 "${PROJECT_VERSION} from ${src}")
endfunction()

_bonded_lattice_headers("${BONDED_LATTICE_ROOT}/src/BONDED_LATTICE" "${CMAKE_BINARY_DIR}/bonded_lattice")
if(TARGET lammps)
  _bonded_lattice_builtin()    # included at the end of LAMMPS' cmake/CMakeLists.txt
else()
  # right after project(lammps): register the styles now, so that LAMMPS' own
  # GenerateStyleHeaders() writes them into its style headers once (a second
  # writing would make every reconfiguration recompile LAMMPS' files that include
  # them); the rest waits for the end of LAMMPS' cmake/CMakeLists.txt
  if(NOT EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/Modules/StyleHeaderUtils.cmake")
    message(FATAL_ERROR "bonded_lattice_builtin.cmake: give it to LAMMPS' own CMake build "
                        "(-S <lammps>/cmake); ${CMAKE_CURRENT_SOURCE_DIR} has no "
                        "Modules/StyleHeaderUtils.cmake")
  endif()
  include("${CMAKE_CURRENT_SOURCE_DIR}/Modules/StyleHeaderUtils.cmake")
  _bonded_lattice_register("${CMAKE_BINARY_DIR}/bonded_lattice")
  cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL _bonded_lattice_builtin)
endif()
