# Helpers shared by every layers target: warnings, the layers::<name> alias,
# the plugin convention (a shared library in bin/plugins named
# liblayers_plugin_<name>.so that links layers::zoo), and the install
# layout of layers/core/install_paths.h:
#   <prefix>/bin/layers, <prefix>/lib/liblayers_<name>.so,
#   <prefix>/lib/layers/plugins/, <prefix>/share/layers/{assets,configs}
# (`cmake --install build --prefix P`; every RPATH is relative, so the
# prefix can move).

function(layers_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  if(LAYERS_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# layers_library(<name> SOURCES ... DEPS ... [PRIVATE_DEPS ...])
# Builds shared library layers_<name> with public headers in
# libs/<name>/include, aliased as layers::<name>.
function(layers_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(layers_${name} SHARED ${ARG_SOURCES})
  add_library(layers::${name} ALIAS layers_${name})
  target_include_directories(layers_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(layers_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(layers_${name} PROPERTIES INSTALL_RPATH "$ORIGIN")
  install(TARGETS layers_${name} LIBRARY DESTINATION lib)
  layers_warnings(layers_${name})
endfunction()

# layers_plugin(<name> SOURCES ... [OUTPUT_DIR dir] [DEPS ...])
# A plugin built into the default folder is installed; one built elsewhere
# (the test plugins) is not. Each gets <file>.hash beside it, built and
# installed (the loader checks it before dlopen). Every plugin exports only its entry point
# (plugin_exports.map): its model code stays private to it, so two plugins
# never resolve each other's symbols. Its sources reuse the zoo's
# precompiled torch headers.
set(LAYERS_PLUGIN_EXPORTS_MAP ${CMAKE_CURRENT_LIST_DIR}/plugin_exports.map)
function(layers_plugin name)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES;DEPS" ${ARGN})
  set(installed OFF)
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR ${LAYERS_PLUGIN_OUTPUT_DIRECTORY})
    set(installed ON)
  endif()
  add_library(layers_plugin_${name} MODULE ${ARG_SOURCES})
  target_link_libraries(layers_plugin_${name} PRIVATE layers::zoo ${ARG_DEPS})
  set_target_properties(layers_plugin_${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIR}
    PREFIX "lib"
    BUILD_RPATH "${CMAKE_BINARY_DIR}/lib"
    INSTALL_RPATH "$ORIGIN/../.."
    DEFINE_SYMBOL ""
    LINK_DEPENDS ${LAYERS_PLUGIN_EXPORTS_MAP})
  target_link_options(layers_plugin_${name} PRIVATE "LINKER:--version-script=${LAYERS_PLUGIN_EXPORTS_MAP}")
  layers_zoo_pch(layers_plugin_${name})
  # Its content hash beside it (<file>.hash, zoo/plugin_hash.h), after each
  # link and again after install (which rewrites its RPATH).
  add_dependencies(layers_plugin_${name} layers_plugin_hash)
  add_custom_command(TARGET layers_plugin_${name} POST_BUILD
    COMMAND layers_plugin_hash $<TARGET_FILE:layers_plugin_${name}> VERBATIM)
  if(installed)
    install(TARGETS layers_plugin_${name} LIBRARY DESTINATION lib/layers/plugins)
    install(CODE "execute_process(COMMAND \"$<TARGET_FILE:layers_plugin_hash>\"
        \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/layers/plugins/$<TARGET_FILE_NAME:layers_plugin_${name}>\"
        RESULT_VARIABLE rc)
      if(rc)
        message(FATAL_ERROR \"layers_plugin_hash failed for $<TARGET_FILE_NAME:layers_plugin_${name}>\")
      endif()")
  endif()
  layers_warnings(layers_plugin_${name})
endfunction()
