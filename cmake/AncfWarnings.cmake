# Common compile options for every ancf target: warnings on, optional sanitizers.
add_library(ancf_options INTERFACE)
target_compile_options(ancf_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
if(ANCF_SANITIZE)
  target_compile_options(ancf_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                -fno-sanitize-recover=undefined)
  target_link_options(ancf_options INTERFACE -fsanitize=address,undefined)
endif()
if(ANCF_FUZZ)
  # Coverage instrumentation for libFuzzer in every library; only the fuzz target links its main.
  target_compile_options(ancf_options INTERFACE -fsanitize=fuzzer-no-link)
endif()

# ancf_add_layer(NAME sources... DEPS libs...) : one static library per architectural layer,
# position-independent (the Python module links them into a shared object) and installed as
# ancf::NAME (cmake/AncfInstall.cmake). The warning options stay with the build tree.
function(ancf_add_layer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(ancf_${name} STATIC ${ARG_SOURCES})
  add_library(ancf::${name} ALIAS ancf_${name})
  set_target_properties(ancf_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME ${name})
  target_include_directories(ancf_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                 $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(ancf_${name} PUBLIC $<BUILD_INTERFACE:ancf_options> ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY ANCF_LAYERS ancf_${name})
endfunction()
