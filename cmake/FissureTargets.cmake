# Helpers that give every Fissure target the same flags and layout.

add_library(fissure_build_flags INTERFACE)
target_compile_options(fissure_build_flags INTERFACE -Wall -Wextra -Wpedantic -Wno-unused-parameter
  # GCC 12 false positives in system headers: PR 105329 (-Wrestrict on std::string concatenation)
  # and PR 105593 (AVX-512 intrinsics' "__Y may be used uninitialized" through Eigen).
  -Wno-restrict -Wno-maybe-uninitialized
  # sqrt without errno: lets loops that take square roots vectorise (nothing reads errno).
  -fno-math-errno)
if(FISSURE_WARNINGS_AS_ERRORS)
  target_compile_options(fissure_build_flags INTERFACE -Werror)
endif()
# The instruction set is part of every module's interface: Eigen's fixed-size types change
# alignment with AVX, so code built without the flag that links a module built with it breaks
# (a probe without it crashed in ~TetMesh with "double free"). Modules therefore pass it on.
add_library(fissure_arch_flags INTERFACE)
if(FISSURE_NATIVE)
  # The stress kernel and the modal products vectorise with AVX2/AVX-512. Results are
  # deterministic on one machine; they are not promised bit-identical across CPUs.
  target_compile_options(fissure_arch_flags INTERFACE -march=native)
endif()
target_link_libraries(fissure_build_flags INTERFACE fissure_arch_flags)

# fissure_add_module(<name> SOURCES ... PUBLIC_DEPS ... PRIVATE_DEPS ...)
# Creates the library target fissure_<name> with the alias Fissure::<name>. Public headers live in
# include/fissure/<name>/. Only the listed dependencies are linked, so the module graph is written
# down here and checked by scripts/check-module-includes.sh.
function(fissure_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(fissure_${name} STATIC ${ARG_SOURCES})
  add_library(Fissure::${name} ALIAS fissure_${name})
  target_include_directories(fissure_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include
                                             PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}
                                                     # private headers shared by modules (json_fields.hpp)
                                                     ${PROJECT_SOURCE_DIR}/src/shared)
  target_link_libraries(fissure_${name} PUBLIC fissure_arch_flags ${ARG_PUBLIC_DEPS}
                                        PRIVATE fissure_build_flags ${ARG_PRIVATE_DEPS})
endfunction()

# fissure_add_test(<name> SOURCES ... DEPS ... [LABELS ...] [TIMEOUT s])
# One GoogleTest executable; each TEST becomes a CTest case carrying the labels.
function(fissure_add_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE fissure_build_flags fissure_test_support ${ARG_DEPS}
                                        GTest::gtest GTest::gtest_main)
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT}
      # Caches (tet meshes, modal bases) go to the build tree, never to the user's home.
      ENVIRONMENT "FISSURE_CACHE_DIR=${PROJECT_BINARY_DIR}/test-cache"
    DISCOVERY_TIMEOUT 60)
endfunction()
