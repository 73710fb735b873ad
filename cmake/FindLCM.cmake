# Finds LCM 1.3 as packaged by Debian (liblcm-dev, liblcm-bin): no CMake config, and an lcm.pc
# that needs glib headers the package does not pull in, so the header, library and lcm-gen are
# located directly. Defines LCM::lcm and LCM_GEN_EXECUTABLE.
find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp)
find_library(LCM_LIBRARY lcm)
find_program(LCM_GEN_EXECUTABLE lcm-gen)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LCM REQUIRED_VARS LCM_LIBRARY LCM_INCLUDE_DIR LCM_GEN_EXECUTABLE)
if(LCM_FOUND AND NOT TARGET LCM::lcm)
  add_library(LCM::lcm UNKNOWN IMPORTED)
  set_target_properties(LCM::lcm PROPERTIES
    IMPORTED_LOCATION "${LCM_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LCM_INCLUDE_DIR}")
endif()
