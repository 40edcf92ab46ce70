# HDF5 for the writers. An MPI build takes Debian's parallel flavour
# (libhdf5-openmpi-dev) when it is installed, so that the ranks write one file
# together; TALUS_PARALLEL_HDF5 says whether they can. Without it an MPI run
# gathers the particles to rank 0, which writes alone.
if(TALUS_MPI)
  set(HDF5_PREFER_PARALLEL TRUE)
endif()
find_package(HDF5 REQUIRED COMPONENTS C)
set(TALUS_PARALLEL_HDF5 OFF)
if(TALUS_MPI AND HDF5_IS_PARALLEL)
  set(TALUS_PARALLEL_HDF5 ON)
elseif(TALUS_MPI)
  message(STATUS "Talus: HDF5 is the serial flavour; install libhdf5-openmpi-dev for one file written by all ranks")
endif()
message(STATUS "Talus parallel HDF5: ${TALUS_PARALLEL_HDF5} (${HDF5_C_LIBRARIES})")

# What a target that includes hdf5.h links: the parallel flavour's header
# includes mpi.h.
add_library(talus_hdf5 INTERFACE)
target_include_directories(talus_hdf5 INTERFACE ${HDF5_C_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS})
target_compile_definitions(talus_hdf5 INTERFACE ${HDF5_C_DEFINITIONS} ${HDF5_DEFINITIONS})
target_link_libraries(talus_hdf5 INTERFACE ${HDF5_C_LIBRARIES})
if(TALUS_PARALLEL_HDF5)
  target_link_libraries(talus_hdf5 INTERFACE MPI::MPI_C)
  target_compile_definitions(talus_hdf5 INTERFACE TALUS_PARALLEL_HDF5=1 OMPI_SKIP_MPICXX=1 MPICH_SKIP_MPICXX=1)
endif()
