# The test helpers every test binary is made with, included from the
# top-level CMakeLists.txt (when LAYERS_BUILD_TESTS is on) before plugins/,
# so that each plugins/<name>/CMakeLists.txt can build its own tests
# (plugins/<name>/test) as well as tests/ can.
find_package(GTest REQUIRED)
include(GoogleTest)

# layers_test_executable(<name> SOURCES ... DEPS ...): a GoogleTest binary
# with tests/support (layers_test_support) and the paths of test_paths.h
# compiled in.
function(layers_test_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} layers_test_support GTest::gtest GTest::gtest_main Threads::Threads)
  layers_warnings(${name})
  target_compile_definitions(${name} PRIVATE
    LAYERS_TEST_BIN="${CMAKE_BINARY_DIR}/bin/layers"
    LAYERS_TEST_PLUGIN_DIR="${CMAKE_BINARY_DIR}/tests/plugins"
    LAYERS_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()

# layers_test_needs_models(<target>): builds the `layers` binary and every
# model plugin of this build before <target>.
function(layers_test_needs_models target)
  add_dependencies(${target} layers)
  foreach(plugin static skinned layersnet deepsd mgnet)
    if(TARGET layers_plugin_${plugin})
      add_dependencies(${target} layers_plugin_${plugin})
    endif()
  endforeach()
endfunction()

# layers_test(<name> SOURCES ... DEPS ...): one GoogleTest binary whose
# tests are registered with ctest individually.
function(layers_test name)
  layers_test_executable(${name} ${ARGN})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
endfunction()

# layers_model_test(<plugin> <name> SOURCES ... [DEPS ...]): the unit tests
# of plugins/<plugin>: a layers_test linking layers_<plugin>_model, built
# after the plugin module they may load.
function(layers_model_test plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  layers_test(${name} SOURCES ${ARG_SOURCES} DEPS layers_${plugin}_model ${ARG_DEPS})
  add_dependencies(${name} layers_plugin_${plugin})
endfunction()

# layers_test_uses_browser_tools(<target>): the test may run node with the
# npm tools of tests/browser (puppeteer-core driving Debian's
# chromium-headless-shell; the Khronos gltf-validator). It gets their
# paths as LAYERS_TEST_NODE, LAYERS_TEST_CHROMIUM ("" where CMake found
# none) and LAYERS_TEST_BROWSER_DIR, and skips itself, saying which is
# missing, without them.
find_program(LAYERS_NODE_PROGRAM node)
find_program(LAYERS_CHROMIUM_PROGRAM chromium-headless-shell)
function(layers_test_uses_browser_tools target)
  set(node "${LAYERS_NODE_PROGRAM}")
  set(chromium "${LAYERS_CHROMIUM_PROGRAM}")
  if(NOT LAYERS_NODE_PROGRAM)
    set(node "")
  endif()
  if(NOT LAYERS_CHROMIUM_PROGRAM)
    set(chromium "")
  endif()
  target_compile_definitions(${target} PRIVATE LAYERS_TEST_NODE="${node}" LAYERS_TEST_CHROMIUM="${chromium}"
    LAYERS_TEST_BROWSER_DIR="${PROJECT_SOURCE_DIR}/tests/browser")
endfunction()
