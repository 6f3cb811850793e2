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

# ancf_add_layer(NAME sources... DEPS libs...) : one static library per architectural layer.
function(ancf_add_layer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(ancf_${name} STATIC ${ARG_SOURCES})
  add_library(ancf::${name} ALIAS ancf_${name})
  target_include_directories(ancf_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(ancf_${name} PUBLIC ancf_options ${ARG_DEPS})
endfunction()
