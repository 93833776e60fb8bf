# Every dependency is a Debian 12 package; nothing is downloaded at configure time.
# scripts/install-deps.sh installs them.

find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# Spectra 1.0 is header-only; Debian ships no CMake config for it.
find_path(SPECTRA_INCLUDE_DIR Spectra/SymGEigsShiftSolver.h REQUIRED)
add_library(fissure_spectra INTERFACE)
target_include_directories(fissure_spectra SYSTEM INTERFACE ${SPECTRA_INCLUDE_DIR})
target_link_libraries(fissure_spectra INTERFACE Eigen3::Eigen)
add_library(Fissure::Spectra ALIAS fissure_spectra)

# CHOLMOD (SuiteSparse 5.12): no CMake config in Debian 12.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(fissure_cholmod INTERFACE)
target_include_directories(fissure_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(fissure_cholmod INTERFACE ${CHOLMOD_LIBRARY} ${SUITESPARSE_CONFIG_LIBRARY})
add_library(Fissure::Cholmod ALIAS fissure_cholmod)

# gmsh 4.8 C++ API (libgmsh-dev): header gmsh.h, library libgmsh. Only the io tests link it,
# to open every file Fissure writes with gmsh itself; Fissure writes and reads MSH with its own
# code, so no command loads libgmsh's ~53 shared libraries (docs/architecture.md).
if(FISSURE_BUILD_TESTS)
  find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
  find_library(GMSH_LIBRARY gmsh REQUIRED)
  add_library(fissure_gmsh INTERFACE)
  target_include_directories(fissure_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
  target_link_libraries(fissure_gmsh INTERFACE ${GMSH_LIBRARY})
  add_library(Fissure::Gmsh ALIAS fissure_gmsh)
endif()

find_package(CGAL 5.5 REQUIRED)
find_package(assimp REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)

if(FISSURE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(FISSURE_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
if(FISSURE_BUILD_STUDIO)
  find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets OpenGL Test)
  find_package(OpenGL REQUIRED)
endif()
