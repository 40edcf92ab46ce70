# talus_add_plugin(NAME SOURCES file... [LINK target...])
#
# Builds a Talus plugin: a shared library with hidden visibility, C++20,
# OpenMP and the -march the ABI check compares, linked against libtalus, and
# writes the plugin's manifest (NAME.talus.json, its descriptor as JSON) next
# to it so the host can index plugins without loading them.
function(talus_add_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "OUTPUT_DIRECTORY" "SOURCES;LINK")
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "talus_add_plugin(${name}): SOURCES is required")
  endif()
  add_library(${name} MODULE ${ARG_SOURCES})
  if(TARGET talus)
    set(_talus_lib talus)
    set(_talus_cli talus_cli)
  else()
    set(_talus_lib Talus::talus)
    set(_talus_cli Talus::talus_cli)
  endif()
  target_link_libraries(${name} PRIVATE ${_talus_lib} ${ARG_LINK})
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    CXX_STANDARD 20
    CXX_STANDARD_REQUIRED ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
  elseif(DEFINED TALUS_PLUGIN_OUTPUT_DIRECTORY)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${TALUS_PLUGIN_OUTPUT_DIRECTORY}")
    set_target_properties(${name} PROPERTIES INSTALL_RPATH "$ORIGIN/../..")
    install(TARGETS ${name} LIBRARY DESTINATION "${TALUS_PLUGIN_SUBDIR}")
    install(FILES "$<TARGET_FILE:${name}>.talus.json" DESTINATION "${TALUS_PLUGIN_SUBDIR}")
  endif()
  add_custom_command(TARGET ${name} POST_BUILD
    COMMAND ${_talus_cli} manifest "$<TARGET_FILE:${name}>"
    COMMENT "Writing the Talus manifest of ${name}"
    VERBATIM)
endfunction()
