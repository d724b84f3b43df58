# FindOMPL: Debian's OMPL 1.5 config sets variables only. Wrap them in an imported
# target, OMPL::ompl, that also carries the boost libraries OMPL needs to link.

find_package(ompl CONFIG QUIET)
find_package(Boost 1.74 QUIET COMPONENTS filesystem serialization system)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OMPL
  REQUIRED_VARS OMPL_LIBRARIES OMPL_INCLUDE_DIRS Boost_FOUND
  VERSION_VAR OMPL_VERSION)

if(OMPL_FOUND AND NOT TARGET OMPL::ompl)
  add_library(OMPL::ompl INTERFACE IMPORTED)
  set_target_properties(OMPL::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES};Boost::filesystem;Boost::serialization;Boost::system")
endif()
