# tongue_headers(TARGET [PATH ...])
#
# Gives TARGET an include root of its own, <build>/include/TARGET, that holds links to its own
# headers and nothing else: each PATH (a folder or a header, relative to the tree the target lives
# in, sim_server/ or controllers/; by default the target's own folder) appears there under the
# same relative path, so that "fem/mesh/mesh.hpp" is found by what links fem_mesh and by nothing
# else. An include across the layers then fails to compile where it is written (the Layering
# tests name the rule it breaks).
function(tongue_headers target)
  set(paths ${ARGN})
  set(tree_dir "")
  foreach(tree sim_server controllers)
    string(FIND "${CMAKE_CURRENT_SOURCE_DIR}/" "${PROJECT_SOURCE_DIR}/${tree}/" at)
    if(at EQUAL 0)
      set(tree_dir "${PROJECT_SOURCE_DIR}/${tree}")
    endif()
  endforeach()
  if(tree_dir STREQUAL "")
    message(FATAL_ERROR "tongue_headers(${target}): ${CMAKE_CURRENT_SOURCE_DIR} is not under "
                        "sim_server/ or controllers/")
  endif()
  if(NOT paths)
    file(RELATIVE_PATH own "${tree_dir}" "${CMAKE_CURRENT_SOURCE_DIR}")
    set(paths "${own}")
  endif()
  set(root "${PROJECT_BINARY_DIR}/include/${target}")
  foreach(path IN LISTS paths)
    if(NOT EXISTS "${tree_dir}/${path}")
      message(FATAL_ERROR "tongue_headers(${target}): no ${tree_dir}/${path}")
    endif()
    get_filename_component(parent "${root}/${path}" DIRECTORY)
    file(MAKE_DIRECTORY "${parent}")
    if(IS_SYMLINK "${root}/${path}")
      file(REMOVE "${root}/${path}")
    endif()
    file(CREATE_LINK "${tree_dir}/${path}" "${root}/${path}" SYMBOLIC)
  endforeach()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE "${root}")
  else()
    target_include_directories(${target} PUBLIC "${root}")
  endif()
endfunction()
