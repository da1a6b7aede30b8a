# Per-target settings: C++20, warnings, optional -Werror and sanitizers. No global flags.
function(vdg_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow $<$<BOOL:${VDG_WERROR}>:-Werror>)
  if(VDG_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  endif()
endfunction()

# vdg_add_module(NAME SOURCES ... DEPS ...): library vdg_NAME with public headers in include/.
function(vdg_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(vdg_${name} STATIC ${ARG_SOURCES})
  add_library(vdg::${name} ALIAS vdg_${name})
  target_include_directories(vdg_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(vdg_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  vdg_target_defaults(vdg_${name})
endfunction()

# vdg_add_test(NAME SOURCES ... DEPS ...): a GoogleTest executable registered with CTest.
function(vdg_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE VDG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  vdg_target_defaults(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ENVIRONMENT "VDG_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
