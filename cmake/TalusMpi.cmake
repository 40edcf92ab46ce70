# The MPI build (DESIGN.md principle 9): Open MPI for messages, Zoltan for the
# partition. Sets TALUS_MPI (ON/OFF) from TALUS_WITH_MPI; with ON it defines
# the imported target Talus::zoltan. The serial build needs neither.
set(TALUS_MPI OFF)
if(NOT TALUS_WITH_MPI STREQUAL "OFF")
  find_package(MPI COMPONENTS C)
  find_path(ZOLTAN_INCLUDE_DIR zoltan.h PATH_SUFFIXES trilinos)
  find_library(ZOLTAN_LIBRARY NAMES trilinos_zoltan zoltan)
  if(MPI_C_FOUND AND ZOLTAN_INCLUDE_DIR AND ZOLTAN_LIBRARY)
    set(TALUS_MPI ON)
    add_library(Talus::zoltan UNKNOWN IMPORTED)
    set_target_properties(Talus::zoltan PROPERTIES IMPORTED_LOCATION "${ZOLTAN_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${ZOLTAN_INCLUDE_DIR}"
                          INTERFACE_LINK_LIBRARIES MPI::MPI_C)
  elseif(TALUS_WITH_MPI STREQUAL "ON")
    message(FATAL_ERROR "TALUS_WITH_MPI=ON needs Open MPI (libopenmpi-dev) and Zoltan (libtrilinos-zoltan-dev)")
  endif()
endif()
message(STATUS "Talus MPI build: ${TALUS_MPI}")
