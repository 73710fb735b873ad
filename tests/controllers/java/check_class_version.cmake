# cmake -DJARS="a.jar;b.jar" -DWORK_DIR=dir -P check_class_version.cmake
# Fails unless every class file in the jars has class-file major version 52 (Java 8): bytes 6-7
# of a class file, after the magic number CAFEBABE and the minor version.
foreach(jar IN LISTS JARS)
  if(NOT EXISTS "${jar}")
    message(FATAL_ERROR "${jar} does not exist: build the project first")
  endif()
  get_filename_component(name "${jar}" NAME_WE)
  set(dir "${WORK_DIR}/${name}")
  file(REMOVE_RECURSE "${dir}")
  file(MAKE_DIRECTORY "${dir}")
  # A jar is a zip archive, which cmake -E tar reads.
  execute_process(COMMAND "${CMAKE_COMMAND}" -E tar xf "${jar}" WORKING_DIRECTORY "${dir}"
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "cannot unpack ${jar}")
  endif()
  file(GLOB_RECURSE classes "${dir}/*.class")
  list(LENGTH classes count)
  if(count EQUAL 0)
    message(FATAL_ERROR "${jar} holds no class file")
  endif()
  foreach(class IN LISTS classes)
    file(READ "${class}" header LIMIT 8 HEX)
    if(NOT header STREQUAL "cafebabe00000034")
      message(FATAL_ERROR "${class} (from ${jar}) starts with ${header}, not cafebabe00000034 "
                          "(Java 8, major version 52)")
    endif()
  endforeach()
  message(STATUS "${jar}: ${count} class files, all Java 8 (major version 52)")
endforeach()
