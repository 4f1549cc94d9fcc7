# OpenFOAM v1912 from Debian 12 packages.
#
# Debian ships OpenFOAM's shared libraries (in /usr/lib) and binaries (blockMesh, decomposePar, ...
# in /usr/bin) but no headers; scripts/install-deps.sh extracts the matching source package and
# builds the lnInclude link farms. This module turns that into:
#
#   mixflow_openfoam     INTERFACE target: include dirs, compile definitions/options and the
#                        libraries an incompressible VOF solver needs (link it, nothing else).
#   MIXFLOW_FOAM_ENV     environment an OpenFOAM program needs at run time, as a list for
#                        set_tests_properties(<test> PROPERTIES ENVIRONMENT "${MIXFLOW_FOAM_ENV}").
#   MIXFLOW_FOAM_<TOOL>  paths of OpenFOAM utilities used by tests: BLOCKMESH, DECOMPOSEPAR,
#                        RECONSTRUCTPAR, POSTPROCESS.
#
# Build facts (docs / shared/spec/build-notes.md): Debian built OpenFOAM with WM_DP,
# WM_LABEL_SIZE=32, Opt, system Open MPI; /usr/lib/libPstream.so is the MPI variant.

include_guard(GLOBAL)

set(MIXFLOW_OPENFOAM_SRC "/opt/mixflow-deps/openfoam-src"
    CACHE PATH "OpenFOAM v1912 source tree with lnInclude link farms (made by scripts/install-deps.sh)")
set(MIXFLOW_OPENFOAM_LIBDIR "/usr/lib"
    CACHE PATH "Directory holding Debian's OpenFOAM shared libraries (libOpenFOAM.so, ...)")
set(MIXFLOW_OPENFOAM_PROJECT_DIR "/usr/share/openfoam"
    CACHE PATH "OpenFOAM installation data directory; exported as WM_PROJECT_DIR at run time")

if(NOT EXISTS "${MIXFLOW_OPENFOAM_SRC}/src/finiteVolume/lnInclude/fvCFD.H")
  message(FATAL_ERROR
    "OpenFOAM headers not found under MIXFLOW_OPENFOAM_SRC='${MIXFLOW_OPENFOAM_SRC}' "
    "(expected src/finiteVolume/lnInclude/fvCFD.H). Debian ships no OpenFOAM headers: run "
    "scripts/install-deps.sh (it extracts Debian's openfoam source package and makes the "
    "lnInclude link farms), or pass -DMIXFLOW_OPENFOAM_SRC=<dir> pointing at such a tree.")
endif()

set(_mixflow_foam_src "${MIXFLOW_OPENFOAM_SRC}/src")
set(_mixflow_foam_incdirs
    OpenFOAM
    OSspecific/POSIX
    finiteVolume
    meshTools
    fvOptions
    sampling
    dynamicMesh
    dynamicFvMesh
    transportModels
    transportModels/twoPhaseMixture
    transportModels/interfaceProperties
    transportModels/immiscibleIncompressibleTwoPhaseMixture
    transportModels/incompressible
    TurbulenceModels/turbulenceModels
    TurbulenceModels/incompressible)

set(_mixflow_foam_includes "")
foreach(_d IN LISTS _mixflow_foam_incdirs)
  if(_d STREQUAL "transportModels")
    # OpenFOAM solvers include e.g. "incompressible/singlePhaseTransportModel/..." relative to this.
    set(_p "${_mixflow_foam_src}/transportModels")
  else()
    set(_p "${_mixflow_foam_src}/${_d}/lnInclude")
  endif()
  if(NOT IS_DIRECTORY "${_p}")
    message(FATAL_ERROR
      "OpenFOAM include directory '${_p}' is missing (incomplete tree under "
      "MIXFLOW_OPENFOAM_SRC='${MIXFLOW_OPENFOAM_SRC}'). Re-run scripts/install-deps.sh "
      "(delete ${MIXFLOW_OPENFOAM_SRC}/.mixflow-lninclude-done first to force a fresh extraction).")
  endif()
  list(APPEND _mixflow_foam_includes "${_p}")
endforeach()

# Libraries, in wmake's order. Found as full paths so the build fails at configure time, not link time.
set(_mixflow_foam_libnames
    finiteVolume fvOptions meshTools sampling dynamicFvMesh
    incompressibleTransportModels interfaceProperties immiscibleIncompressibleTwoPhaseMixture
    turbulenceModels incompressibleTurbulenceModels
    OpenFOAM Pstream)
set(_mixflow_foam_libs "")
foreach(_l IN LISTS _mixflow_foam_libnames)
  find_library(MIXFLOW_FOAM_LIB_${_l} NAMES ${_l}
               PATHS "${MIXFLOW_OPENFOAM_LIBDIR}" NO_DEFAULT_PATH)
  if(NOT MIXFLOW_FOAM_LIB_${_l})
    message(FATAL_ERROR
      "OpenFOAM library lib${_l}.so not found in MIXFLOW_OPENFOAM_LIBDIR='${MIXFLOW_OPENFOAM_LIBDIR}'. "
      "Install Debian's openfoam/libopenfoam packages (scripts/install-deps.sh does).")
  endif()
  list(APPEND _mixflow_foam_libs "${MIXFLOW_FOAM_LIB_${_l}}")
endforeach()

if(NOT TARGET mixflow_openfoam)
  add_library(mixflow_openfoam INTERFACE)
  # SYSTEM: OpenFOAM's headers warn a lot under C++17 (std::iterator etc.); keep our warnings ours.
  target_include_directories(mixflow_openfoam SYSTEM INTERFACE ${_mixflow_foam_includes})
  target_compile_definitions(mixflow_openfoam INTERFACE
      OPENFOAM=1912 WM_DP WM_LABEL_SIZE=32 NoRepository)
  target_compile_options(mixflow_openfoam INTERFACE
      -m64 -pthread -fPIC -ftemplate-depth-100)
  # --no-as-needed: OpenFOAM registers boundary conditions, schemes and models in run-time selection
  # tables from static constructors; a library the executable never references by symbol must still
  # be loaded. Link options come before the libraries on the link line, so it covers all of them.
  target_link_options(mixflow_openfoam INTERFACE -m64 -pthread "LINKER:--no-as-needed")
  target_link_libraries(mixflow_openfoam INTERFACE ${_mixflow_foam_libs} dl m)
  add_library(mixflow::openfoam ALIAS mixflow_openfoam)
endif()

# Run-time environment: without WM_PROJECT_DIR, OpenFOAM fails with
# "Could not find mandatory etc entry 'controlDict'" (FOAM_ETC alone is not enough).
set(MIXFLOW_FOAM_ENV "WM_PROJECT_DIR=${MIXFLOW_OPENFOAM_PROJECT_DIR}")

# Utilities from Debian's openfoam package (used by tests and case scripts).
find_program(MIXFLOW_FOAM_BLOCKMESH blockMesh PATHS /usr/bin)
find_program(MIXFLOW_FOAM_DECOMPOSEPAR decomposePar PATHS /usr/bin)
find_program(MIXFLOW_FOAM_RECONSTRUCTPAR reconstructPar PATHS /usr/bin)
find_program(MIXFLOW_FOAM_POSTPROCESS postProcess PATHS /usr/bin)

message(STATUS "OpenFOAM: headers ${MIXFLOW_OPENFOAM_SRC}, libraries ${MIXFLOW_OPENFOAM_LIBDIR}, "
               "WM_PROJECT_DIR=${MIXFLOW_OPENFOAM_PROJECT_DIR}")

unset(_mixflow_foam_src)
unset(_mixflow_foam_incdirs)
unset(_mixflow_foam_includes)
unset(_mixflow_foam_libnames)
unset(_mixflow_foam_libs)
unset(_d)
unset(_p)
unset(_l)
