# Finds OpenFOAM v1912 as Debian ships it: libraries in /usr/lib, headers from
# the Debian source package prepared by scripts/setup (lnInclude folders).
#
# Input:  FSI_OPENFOAM_SRC (cache; default ~/.cache/fsi-toolkit/openfoam-v1912)
# Output: OpenFOAM::OpenFOAM, an interface target with the include folders,
#         compile definitions and libraries a steady incompressible solver with
#         mesh motion needs; OpenFOAM_LIBRARY_DIR.
set(_of_default "$ENV{HOME}/.cache/fsi-toolkit/openfoam-v1912")
if(DEFINED ENV{FSI_CACHE})
  set(_of_default "$ENV{FSI_CACHE}/openfoam-v1912")
endif()
set(FSI_OPENFOAM_SRC "${_of_default}" CACHE PATH "OpenFOAM v1912 source tree with lnInclude folders (made by scripts/setup)")

find_library(OpenFOAM_CORE_LIBRARY OpenFOAM PATHS /usr/lib /usr/lib/openfoam/lib NO_DEFAULT_PATH)
get_filename_component(OpenFOAM_LIBRARY_DIR "${OpenFOAM_CORE_LIBRARY}" DIRECTORY)

set(_of_inc_rel
  OpenFOAM OSspecific/POSIX finiteVolume meshTools fileFormats surfMesh
  dynamicMesh dynamicFvMesh fvMotionSolver sampling functionObjects/forces
  TurbulenceModels/turbulenceModels TurbulenceModels/incompressible
  transportModels/incompressible)
set(OpenFOAM_INCLUDE_DIRS "")
set(_of_missing "")
foreach(_d ${_of_inc_rel})
  if(IS_DIRECTORY "${FSI_OPENFOAM_SRC}/src/${_d}/lnInclude")
    list(APPEND OpenFOAM_INCLUDE_DIRS "${FSI_OPENFOAM_SRC}/src/${_d}/lnInclude")
  else()
    list(APPEND _of_missing "${_d}")
  endif()
endforeach()
# transportModels keeps some headers outside lnInclude.
list(APPEND OpenFOAM_INCLUDE_DIRS "${FSI_OPENFOAM_SRC}/src/transportModels")

set(_of_libs finiteVolume meshTools dynamicMesh dynamicFvMesh fvMotionSolvers
    turbulenceModels incompressibleTurbulenceModels incompressibleTransportModels
    forces fileFormats surfMesh OpenFOAM)
set(OpenFOAM_LIBRARIES "")
foreach(_l ${_of_libs})
  find_library(OpenFOAM_${_l}_LIBRARY ${_l} PATHS ${OpenFOAM_LIBRARY_DIR} NO_DEFAULT_PATH)
  if(OpenFOAM_${_l}_LIBRARY)
    list(APPEND OpenFOAM_LIBRARIES "${OpenFOAM_${_l}_LIBRARY}")
  else()
    list(APPEND _of_missing "lib${_l}.so")
  endif()
  mark_as_advanced(OpenFOAM_${_l}_LIBRARY)
endforeach()

set(_of_headers_ok FALSE)
if(EXISTS "${FSI_OPENFOAM_SRC}/src/finiteVolume/lnInclude/fvCFD.H" AND NOT _of_missing)
  set(_of_headers_ok TRUE)
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenFOAM
  REQUIRED_VARS OpenFOAM_CORE_LIBRARY _of_headers_ok
  FAIL_MESSAGE "OpenFOAM v1912 not usable (missing: ${_of_missing}). Run ./scripts/setup, or configure with -DFSI_WITH_FLUID=OFF")

if(OpenFOAM_FOUND AND NOT TARGET OpenFOAM::OpenFOAM)
  add_library(OpenFOAM::OpenFOAM INTERFACE IMPORTED)
  set_target_properties(OpenFOAM::OpenFOAM PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OpenFOAM_INCLUDE_DIRS}"
    INTERFACE_COMPILE_DEFINITIONS "OPENFOAM=1912;WM_DP;WM_LABEL_SIZE=32;NoRepository;linux64;WM_ARCH_OPTION=64"
    INTERFACE_COMPILE_OPTIONS "-m64;-ftemplate-depth-100;-Wno-old-style-cast;-Wno-unused-parameter;-Wno-deprecated-copy;-Wno-class-memaccess"
    INTERFACE_LINK_OPTIONS "LINKER:--no-as-needed"
    INTERFACE_LINK_LIBRARIES "${OpenFOAM_LIBRARIES};dl;m")
endif()
