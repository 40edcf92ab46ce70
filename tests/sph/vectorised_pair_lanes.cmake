# Whether the compiler Talus is built with vectorises the term loop of the
# mutual pass's lanes (sph/mutual_pass.hpp), from its own vectorisation
# report (GCC's -fopt-info-vec-optimized) on vectorised_pair_lanes.cpp with
# Talus' -march. Arguments: CXX, CXX_ID, MARCH, INCLUDES (;-list), SOURCE,
# HEADER, WORK.
if(NOT CXX_ID STREQUAL "GNU")
  message("SKIPPED: the vectorisation report is read from GCC's -fopt-info (compiler: ${CXX_ID})")
  return()
endif()
if(MARCH STREQUAL "")
  message("SKIPPED: built without -march (TALUS_MARCH is empty): the lanes are vectorised for a named target")
  return()
endif()

# The loop is the line after its marker comment.
file(READ "${HEADER}" text)
string(FIND "${text}" "// The terms, lane by lane:" at)
if(at LESS 0)
  message(FATAL_ERROR "no marker comment for the lane loop in ${HEADER}")
endif()
string(SUBSTRING "${text}" 0 ${at} before)
string(REGEX MATCHALL "\n" newlines "${before}")
list(LENGTH newlines count)
math(EXPR loop_line "${count} + 2")
get_filename_component(header_name "${HEADER}" NAME)

set(flags -std=c++20 -O3 -DNDEBUG -march=${MARCH} -fopenmp -fopt-info-vec-optimized)
foreach(dir IN LISTS INCLUDES)
  list(APPEND flags -I${dir})
endforeach()
foreach(terms 1 2 3 4 5 6)
  execute_process(COMMAND ${CXX} ${flags} -DTERMS=${terms} -c ${SOURCE} -o ${WORK}/vectorised_pair_lanes_${terms}.o
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE report)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "compiling ${SOURCE} (TERMS=${terms}) failed:\n${report}")
  endif()
  if(NOT report MATCHES "${header_name}:${loop_line}:[0-9]+: optimized: loop vectorized using ([0-9]+) byte vectors")
    message(FATAL_ERROR "term set ${terms}: the lane loop at ${header_name}:${loop_line} was not vectorised "
                        "with -march=${MARCH}. The report:\n${report}")
  endif()
  message("term set ${terms}: the lane loop at ${header_name}:${loop_line} is vectorised with "
          "${CMAKE_MATCH_1}-byte vectors (-march=${MARCH})")
endforeach()
