# VIGRA's linear algebra (Debian's libvigraimpex-dev): header-only for what this project uses
# (vigra/regression.hxx), so the target carries the include directory alone. Debian ships no
# CMake package for it.
find_path(VIGRA_INCLUDE_DIR NAMES vigra/regression.hxx)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(VIGRA REQUIRED_VARS VIGRA_INCLUDE_DIR)
if(VIGRA_FOUND AND NOT TARGET VIGRA::headers)
  add_library(VIGRA::headers INTERFACE IMPORTED)
  set_target_properties(VIGRA::headers PROPERTIES INTERFACE_INCLUDE_DIRECTORIES
                                                  "${VIGRA_INCLUDE_DIR}")
endif()
