# The LAMMPS interfaces that differ between the supported LAMMPS releases
# (src/BONDED_LATTICE/lammps_api_compat.h).  LAMMPS headers carry no version
# number, so each difference is tested by compiling one line against the
# headers in use.  Used by CMakeLists.txt (the plugin) and by
# cmake/bonded_lattice_builtin.cmake (the package compiled into LAMMPS).
#
#   bonded_lattice_check_api(INCLUDES <dirs> DEFINITIONS <-Dflags> LIBRARIES <libs or targets>)
#
# sets BONDED_LATTICE_MINIMUM_IMAGE_FLERR and BONDED_LATTICE_UTILS_PRINT to 1 or 0
# in the caller's scope (written into bonded_lattice_config.h) and stops with an
# error naming the include directories if a plain LAMMPS header does not compile.
include_guard(GLOBAL)
include(CheckCXXSourceCompiles)

function(_bonded_lattice_compiles result code)
  unset(${result} CACHE)                                # re-test when LAMMPS changes
  check_cxx_source_compiles("${code}" ${result})
  set(${result} ${${result}} PARENT_SCOPE)
endfunction()

function(bonded_lattice_check_api)
  cmake_parse_arguments(arg "" "" "INCLUDES;DEFINITIONS;LIBRARIES" ${ARGN})
  set(CMAKE_REQUIRED_INCLUDES ${arg_INCLUDES})
  set(CMAKE_REQUIRED_DEFINITIONS ${arg_DEFINITIONS})
  set(CMAKE_REQUIRED_LIBRARIES ${arg_LIBRARIES})
  set(CMAKE_REQUIRED_QUIET ON)
  set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)    # compile only
  _bonded_lattice_compiles(_bonded_lattice_headers_usable
    "#include \"domain.h\"
     int f(LAMMPS_NS::Domain *domain) { return domain->triclinic; }")
  if(NOT _bonded_lattice_headers_usable)
    message(FATAL_ERROR "BONDED_LATTICE: cannot compile against the LAMMPS headers in "
                        "'${arg_INCLUDES}': see CMakeFiles/CMakeConfigureLog.yaml, and check "
                        "that they are the headers of a LAMMPS and that mpi.h is found")
  endif()
  _bonded_lattice_compiles(_bonded_lattice_minimum_image_flerr
    "#include \"domain.h\"
     void f(LAMMPS_NS::Domain *domain, double *d) { domain->minimum_image(FLERR, d); }")
  _bonded_lattice_compiles(_bonded_lattice_utils_print
    "#include \"utils.h\"
     #include <cstdio>
     void f(FILE *fp) { LAMMPS_NS::utils::print(fp, \"{}\", 1); }")
  foreach(api IN ITEMS MINIMUM_IMAGE_FLERR UTILS_PRINT)
    string(TOLOWER "_bonded_lattice_${api}" found)
    if(${found})
      set(BONDED_LATTICE_${api} 1 PARENT_SCOPE)
      message(STATUS "BONDED_LATTICE: BONDED_LATTICE_${api}=1")
    else()
      set(BONDED_LATTICE_${api} 0 PARENT_SCOPE)
      message(STATUS "BONDED_LATTICE: BONDED_LATTICE_${api}=0")
    endif()
  endforeach()
endfunction()
