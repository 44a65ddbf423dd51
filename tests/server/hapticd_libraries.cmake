# hapticd's direct shared-library needs (readelf -d), checked against the libraries it must not
# map at start: Assimp and its Draco codec (3.3 MB resident even in a plane scene; opened only
# when a scene names a mesh file, meshes/mesh_import_on_demand.hpp) and OpenCV (its codecs map
# ~140 libraries). Both once went in unnoticed: docs/benchmarks.md, hapticd's memory.
# Usage: cmake -DBINARY=path/to/hapticd -P hapticd_libraries.cmake
execute_process(COMMAND readelf -d ${BINARY} OUTPUT_VARIABLE dynamic RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY} failed (${status})")
endif()
string(REGEX MATCHALL "Shared library: \\[[^]]*\\]" needed "${dynamic}")
list(LENGTH needed count)
if(count EQUAL 0)
  message(FATAL_ERROR "readelf -d ${BINARY}: no NEEDED entries read; expected hapticd's libraries")
endif()
foreach(entry ${needed})
  if(entry MATCHES "assimp|draco|opencv")
    message(FATAL_ERROR "${BINARY} links ${entry}; expected it to open mesh files through the mesh import module "
                        "and never to link OpenCV")
  endif()
endforeach()
message(STATUS "${BINARY}: ${count} shared libraries, none of Assimp, Draco or OpenCV")
