/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The LAMMPS interfaces that differ between the supported releases.  The
   installed LAMMPS headers carry no version number, so CMake compiles one
   line against the headers in use and sets (see CMakeLists.txt):

   BONDED_LATTICE_MINIMUM_IMAGE_FLERR  Domain::minimum_image(FLERR, delta)
       (LAMMPS after 4 Feb 2025; before: minimum_image(delta))
   BONDED_LATTICE_UTILS_PRINT          utils::print(FILE *, format, ...)
       (LAMMPS 4 Feb 2025 and later; before: fmt::print)
------------------------------------------------------------------------- */

#ifndef LMP_BONDED_LATTICE_API_COMPAT_H
#define LMP_BONDED_LATTICE_API_COMPAT_H

#include "domain.h"
#include "utils.h"

#include <cstdio>
#include <string>
#include <utility>

#if !defined(BONDED_LATTICE_MINIMUM_IMAGE_FLERR) || !defined(BONDED_LATTICE_UTILS_PRINT)
#error "build the BONDED_LATTICE plugin with its CMakeLists.txt: it tests the LAMMPS interfaces"
#endif

namespace LAMMPS_NS {

// the minimum image of a distance vector in the simulation box
inline void lattice_minimum_image(Domain *domain, double *delta)
{
#if BONDED_LATTICE_MINIMUM_IMAGE_FLERR
  domain->minimum_image(FLERR, delta);
#else
  domain->minimum_image(delta);
#endif
}

// formatted output to a file ({fmt} syntax)
template <typename... Args> void lattice_print(FILE *fp, const std::string &format, Args &&...args)
{
#if BONDED_LATTICE_UTILS_PRINT
  utils::print(fp, format, std::forward<Args>(args)...);
#else
  fmt::vprint(fp, format, fmt::make_format_args(args...));
#endif
}

}    // namespace LAMMPS_NS

#endif
