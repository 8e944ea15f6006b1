# Finds parallel double-precision MUMPS (Debian). Defines MUMPS::dmumps and MUMPS_VARIANT.
# FSI_MUMPS_VARIANT: ptscotch (Debian libmumps-ptscotch-dev: SCOTCH and PT-SCOTCH compiled in,
# which MUMPS' block low-rank clustering, the SCOTCH ordering and the parallel analysis need) or
# plain (libmumps-dev: PORD only; BLR then clusters badly and is kept off). Default: ptscotch
# when found, else plain. MUMPS_HAS_SCOTCH is set for the ptscotch variant.
set(FSI_MUMPS_VARIANT "auto" CACHE STRING "MUMPS build to link: auto, ptscotch or plain")
set_property(CACHE FSI_MUMPS_VARIANT PROPERTY STRINGS auto ptscotch plain)
find_path(MUMPS_INCLUDE_DIR dmumps_c.h PATH_SUFFIXES mumps)
if(NOT FSI_MUMPS_VARIANT STREQUAL "plain")
  find_library(MUMPS_D_PTSCOTCH_LIBRARY dmumps_ptscotch)
  find_library(MUMPS_COMMON_PTSCOTCH_LIBRARY mumps_common_ptscotch)
  find_library(MUMPS_PORD_PTSCOTCH_LIBRARY pord_ptscotch)
endif()
if(MUMPS_D_PTSCOTCH_LIBRARY AND MUMPS_COMMON_PTSCOTCH_LIBRARY)
  set(MUMPS_VARIANT ptscotch)
  set(MUMPS_HAS_SCOTCH TRUE)
  set(MUMPS_D_LIBRARY ${MUMPS_D_PTSCOTCH_LIBRARY})
  set(MUMPS_COMMON_LIBRARY ${MUMPS_COMMON_PTSCOTCH_LIBRARY})
  set(MUMPS_PORD_LIBRARY ${MUMPS_PORD_PTSCOTCH_LIBRARY})
else()
  if(FSI_MUMPS_VARIANT STREQUAL "ptscotch")
    message(FATAL_ERROR "FSI_MUMPS_VARIANT=ptscotch but libdmumps_ptscotch was not found: "
                        "apt-get install libmumps-ptscotch-dev (scripts/setup does)")
  endif()
  set(MUMPS_VARIANT plain)
  set(MUMPS_HAS_SCOTCH FALSE)
  find_library(MUMPS_D_LIBRARY dmumps)
  find_library(MUMPS_COMMON_LIBRARY mumps_common)
  find_library(MUMPS_PORD_LIBRARY pord)
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS REQUIRED_VARS MUMPS_D_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_INCLUDE_DIR)
if(MUMPS_FOUND AND NOT TARGET MUMPS::dmumps)
  message(STATUS "MUMPS: ${MUMPS_VARIANT} (${MUMPS_D_LIBRARY})")
  add_library(MUMPS::dmumps UNKNOWN IMPORTED)
  set(_mumps_extra ${MUMPS_COMMON_LIBRARY})
  if(MUMPS_PORD_LIBRARY)
    list(APPEND _mumps_extra ${MUMPS_PORD_LIBRARY})
  endif()
  set_target_properties(MUMPS::dmumps PROPERTIES IMPORTED_LOCATION "${MUMPS_D_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_mumps_extra};MPI::MPI_C")
  if(MUMPS_HAS_SCOTCH)
    set_property(TARGET MUMPS::dmumps APPEND PROPERTY INTERFACE_COMPILE_DEFINITIONS FSI_MUMPS_HAS_SCOTCH=1)
  endif()
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR MUMPS_D_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_PORD_LIBRARY
                 MUMPS_D_PTSCOTCH_LIBRARY MUMPS_COMMON_PTSCOTCH_LIBRARY MUMPS_PORD_PTSCOTCH_LIBRARY)
