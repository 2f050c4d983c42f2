# ctest plugin_exports: every model plugin in PLUGIN_DIR exports exactly one
# defined dynamic symbol, the entry point (layers_plugin() links with
# cmake/plugin_exports.map). Run as
#   cmake -DNM=<nm> -DPLUGIN_DIR=<build>/bin/plugins -P check_exports.cmake
file(GLOB PLUGINS ${PLUGIN_DIR}/liblayers_plugin_*.so)
list(LENGTH PLUGINS count)
if(count LESS 1)
  message(FATAL_ERROR "${PLUGIN_DIR}: expected model plugins, found none")
endif()
foreach(plugin IN LISTS PLUGINS)
  execute_process(COMMAND ${NM} -D --defined-only ${plugin}
    OUTPUT_VARIABLE symbols RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${plugin}: nm failed: ${err}")
  endif()
  string(REGEX MATCHALL "[^\n]+" lines "${symbols}")
  set(exported "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^.* " "" name "${line}")
    list(APPEND exported ${name})
  endforeach()
  if(NOT exported STREQUAL "layers_plugin_register")
    message(FATAL_ERROR "${plugin}: expected only layers_plugin_register exported, got: ${exported}")
  endif()
  message(STATUS "${plugin}: exports only layers_plugin_register")
endforeach()
