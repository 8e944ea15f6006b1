# Finds parallel double-precision MUMPS (Debian libmumps-dev). Defines MUMPS::dmumps.
find_path(MUMPS_INCLUDE_DIR dmumps_c.h PATH_SUFFIXES mumps)
find_library(MUMPS_D_LIBRARY dmumps)
find_library(MUMPS_COMMON_LIBRARY mumps_common)
find_library(MUMPS_PORD_LIBRARY pord)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS REQUIRED_VARS MUMPS_D_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_INCLUDE_DIR)
if(MUMPS_FOUND AND NOT TARGET MUMPS::dmumps)
  add_library(MUMPS::dmumps UNKNOWN IMPORTED)
  set(_mumps_extra ${MUMPS_COMMON_LIBRARY})
  if(MUMPS_PORD_LIBRARY)
    list(APPEND _mumps_extra ${MUMPS_PORD_LIBRARY})
  endif()
  set_target_properties(MUMPS::dmumps PROPERTIES IMPORTED_LOCATION "${MUMPS_D_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_mumps_extra};MPI::MPI_C")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR MUMPS_D_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_PORD_LIBRARY)
