# Sourced by the scripts: run-time environment for MPI and OpenFOAM.
# SPDX-License-Identifier: GPL-3.0-or-later
FSI_ROOT=${FSI_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
FSI_BUILD_DIR=${FSI_BUILD_DIR:-$FSI_ROOT/build}
export FSI_ROOT FSI_BUILD_DIR
# Open MPI as root, oversubscribed, and all traffic on loopback.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_tcp_if_include=${OMPI_MCA_btl_tcp_if_include:-lo}
export OMPI_MCA_oob_tcp_if_include=${OMPI_MCA_oob_tcp_if_include:-lo}
# OpenFOAM v1912 from Debian: the run-time tree (etc/, controlDict defaults).
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
export FOAM_SIGFPE=${FOAM_SIGFPE:-false}
# Debian's python3 (matplotlib, numpy, meshio); python3 on PATH may be another interpreter.
FSI_PYTHON=${FSI_PYTHON:-/usr/bin/python3}
export FSI_PYTHON
