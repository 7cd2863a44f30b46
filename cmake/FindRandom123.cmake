# FindRandom123: the header-only Random123 counter-based generators
# (Debian: librandom123-dev). Installed with stickslip's package config,
# because the public header stickslip/random_stream.hpp includes
# <Random123/philox.h>, so every consumer of stickslip::core needs it too.
#
# Defines Random123_FOUND, Random123_INCLUDE_DIR and the INTERFACE IMPORTED
# target Random123::Random123 (its include directory is a system one).
find_path(Random123_INCLUDE_DIR Random123/philox.h
  DOC "directory that holds Random123/philox.h")
mark_as_advanced(Random123_INCLUDE_DIR)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Random123 REQUIRED_VARS Random123_INCLUDE_DIR)

if(Random123_FOUND AND NOT TARGET Random123::Random123)
  add_library(Random123::Random123 INTERFACE IMPORTED)
  set_target_properties(Random123::Random123 PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${Random123_INCLUDE_DIR}")
endif()
