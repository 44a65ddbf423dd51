# One precompiled header for the product's targets (libraries, programs, benchmarks; not tests/,
# which have theirs). Included at the end of the top-level CMakeLists.txt, once every target exists.
#
# A unity batch parses Eigen and the standard library once; this header parses them once per tree
# (docs/build.md, "Product precompiled header"). GCC stores in the header some options that the
# code compiled with it then follows, not its own command line: the optimisation level, the aliasing
# rule (-fno-strict-aliasing, which every user of the LCM messages needs), and -pthread's
# _REENTRANT, and position-independent code (-fPIC against the executables' -fPIE: the libraries
# the mesh import module holds, meshes/CMakeLists.txt). So each combination in use gets its own header, and -Winvalid-pch (an error with
# THX_WERROR) stops the build where a target's flags and its header's differ, instead of g++ parsing
# silently, or compiling with the header's rule.
# A source file with options of its own (resonator_kernel.cpp: -O3 -ffp-contract=off) is compiled
# without the header: with it, the AVX-512 kernel no longer matched the scalar reference bit for
# bit (the header's options won over the file's), and ResonatorKernel.EveryVariantMatchesTheScalar-
# Reference caught it. GCC only: clang
# checks a header's flags differently, and the fuzz build (THX_FUZZ, clang) gives libraries flags of
# their own.
option(THX_PRODUCT_PCH "Precompiled header of Eigen and the standard library for product code" ON)
if(NOT THX_PRODUCT_PCH OR THX_FUZZ OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  return()
endif()

set(THX_PRODUCT_PCH_HEADERS <Eigen/Core> <Eigen/Geometry> <algorithm> <array> <cmath> <cstdint>
    <cstdio> <functional> <map> <memory> <optional> <span> <string> <string_view> <vector>)

# Does target t get `marker`'s interface? Through its own links, then only through what each
# dependency passes on (INTERFACE_LINK_LIBRARIES): a library's private links give no compile flags.
function(thx_pch_reaches t marker out)
  set(seen)
  get_target_property(to_visit ${t} LINK_LIBRARIES)
  if(NOT to_visit)
    set(to_visit)
  endif()
  set(found OFF)
  while(to_visit)
    list(POP_FRONT to_visit cur)
    if(cur STREQUAL marker)
      set(found ON)
      break()
    endif()
    if(cur IN_LIST seen OR NOT TARGET ${cur})
      continue()
    endif()
    list(APPEND seen ${cur})
    get_target_property(next ${cur} INTERFACE_LINK_LIBRARIES)
    if(next)
      list(APPEND to_visit ${next})
    endif()
  endwhile()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

# The header target for one combination, made on first use: thx_pch_<opt>_<kind>, with _pic for
# position-independent code.
function(thx_pch_target opt kind pic out)
  set(name thx_pch_${opt}_${kind})
  if(pic)
    string(APPEND name _pic)
  endif()
  if(NOT TARGET ${name})
    add_library(${name} OBJECT ${PROJECT_SOURCE_DIR}/base/pch/pch_owner.cpp)
    target_link_libraries(${name} PRIVATE Eigen3::Eigen)
    if(pic)
      set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      target_compile_options(${name} PRIVATE -fno-semantic-interposition)
    endif()
    if(opt STREQUAL "O1")
      target_compile_options(${name} PRIVATE -O1)
    endif()
    if(kind STREQUAL "lcm")
      target_compile_options(${name} PRIVATE -pthread -fno-strict-aliasing)
    elseif(kind STREQUAL "threads")
      target_compile_options(${name} PRIVATE -pthread)
    endif()
    target_precompile_headers(${name} PRIVATE ${THX_PRODUCT_PCH_HEADERS})
  endif()
  set(${out} ${name} PARENT_SCOPE)
endfunction()

thx_collect_targets(${PROJECT_SOURCE_DIR} "EXECUTABLE;STATIC_LIBRARY;OBJECT_LIBRARY;SHARED_LIBRARY" "tests"
                    thx_product_targets)
foreach(t ${thx_product_targets})
  get_target_property(sources ${t} SOURCES)
  list(FILTER sources INCLUDE REGEX "\\.cpp$")
  if(NOT sources)
    continue()
  endif()
  # thx_messages adds -fno-strict-aliasing (messages/CMakeLists.txt), LCM's pkg-config -pthread.
  thx_pch_reaches(${t} thx_messages uses_messages)
  thx_pch_reaches(${t} PkgConfig::LCM uses_lcm)
  set(kind plain)
  if(uses_messages)
    set(kind lcm)
  elseif(uses_lcm)
    set(kind threads)
  endif()
  set(opt default)
  if(THX_SANITIZE AND t IN_LIST THX_O1_UNDER_SANITIZERS)
    set(opt O1)
  endif()
  get_target_property(pic ${t} POSITION_INDEPENDENT_CODE)
  thx_pch_target(${opt} ${kind} "${pic}" pch)
  target_precompile_headers(${t} REUSE_FROM ${pch})
  get_target_property(target_dir ${t} SOURCE_DIR)
  foreach(source ${sources})
    cmake_path(ABSOLUTE_PATH source BASE_DIRECTORY ${target_dir})
    get_source_file_property(own_options ${source} TARGET_DIRECTORY ${t} COMPILE_OPTIONS)
    get_source_file_property(own_flags ${source} TARGET_DIRECTORY ${t} COMPILE_FLAGS)
    if(own_options OR own_flags)
      set_source_files_properties(${source} TARGET_DIRECTORY ${t} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
    endif()
  endforeach()
  target_compile_options(${t} PRIVATE -Winvalid-pch)
endforeach()
