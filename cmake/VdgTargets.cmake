include(GNUInstallDirs)

# Per-target settings: C++20, warnings, optional -Werror and sanitizers. No global flags.
# The sanitizer link flag is passed on to whatever links the target inside this build tree (tests,
# the app) but never exported: an installed vdg package must not force -fsanitize on its users.
# TEST_CODE (the test programs and their precompiled header): under VDG_SANITIZE their own code is
# instrumented by AddressSanitizer only. vdg's code (the libraries, the tool, the examples) keeps
# both sanitizers, and a test program links both runtimes through the libraries. UBSan's checks of
# the test bodies and of GoogleTest's templates were 30% of a heavy test file's compile
# (tests/io/gltf_test.cpp) and check only the tests' own arithmetic; memory errors in the tests'
# code are still found.
function(vdg_target_defaults target)
  cmake_parse_arguments(ARG "TEST_CODE" "" "" ${ARGN})
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow $<$<BOOL:${VDG_WERROR}>:-Werror>)
  if(VDG_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
  if(VDG_SANITIZE AND ARG_TEST_CODE)
    target_compile_options(${target} PRIVATE -fsanitize=address -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  elseif(VDG_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PUBLIC $<BUILD_INTERFACE:-fsanitize=address,undefined>)
  endif()
endfunction()

# Which package provides an external target that an installed vdg library needs, as the lines (a
# list) the package config (vdgConfig.cmake) runs to find it and as the pkg-config module vdg.pc requires.
# A module that links a new external library adds it here; configuring fails until it does.
function(_vdg_package_of dep out_find out_pc)
  if(dep STREQUAL "Eigen3::Eigen")
    set(find "find_dependency(Eigen3 3.3 NO_MODULE)")
    set(pc eigen3)
  elseif(dep MATCHES "^Qhull::(.+)$")
    set(find "find_dependency(Qhull)")
    set(pc ${CMAKE_MATCH_1})
  elseif(dep STREQUAL "tinyobjloader::tinyobjloader")
    set(find "find_dependency(tinyobjloader)")
    set(pc tinyobjloader)
  elseif(dep STREQUAL "nlohmann_json::nlohmann_json")
    set(find "find_dependency(nlohmann_json 3)")
    set(pc nlohmann_json)
  elseif(dep STREQUAL "TBB::tbb")  # oneTBB: threads of the per-frame evaluation (geom, viewdep)
    set(find "find_dependency(TBB)")
    set(pc tbb)
  elseif(dep MATCHES "^Boost::")
    set(find "find_dependency(Boost)")
    set(pc "")  # Boost ships no pkg-config files; its headers are in the default include path
  elseif(dep STREQUAL "PkgConfig::LUA")  # script: Lua 5.4, whose pkg-config module is lua5.4
    set(pc lua5.4)
    set(find "find_dependency(PkgConfig)" "_vdg_find_pkg(LUA lua5.4)")
  elseif(dep MATCHES "^PkgConfig::(EPOXY|STB|GMP|MPFR)$")  # GMP, MPFR: CGAL's exact numbers (morph, viewdep's key space)
    string(TOLOWER "${CMAKE_MATCH_1}" pc)
    set(find "find_dependency(PkgConfig)" "_vdg_find_pkg(${CMAKE_MATCH_1} ${pc})")
  else()
    message(FATAL_ERROR "vdg_add_module: an installed vdg library links ${dep}, and cmake/VdgTargets.cmake "
                        "does not know which package provides it; add it to _vdg_package_of there")
  endif()
  set(${out_find} "${find}" PARENT_SCOPE)
  set(${out_pc} "${pc}" PARENT_SCOPE)
endfunction()

# A dependency that only lends its headers to the library's own .cpp files: an interface library
# that links nothing (nlohmann_json, Boost::headers). The static library needs nothing from it at
# link time, so it is kept out of the installed package.
function(_vdg_is_header_only dep out)
  set(result FALSE)
  if(TARGET ${dep})
    get_target_property(type ${dep} TYPE)
    get_target_property(links ${dep} INTERFACE_LINK_LIBRARIES)
    if(type STREQUAL "INTERFACE_LIBRARY" AND NOT links)
      set(result TRUE)
    endif()
  endif()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# vdg_add_module(NAME SOURCES ... DEPS ... PRIVATE_DEPS ...): library vdg_NAME (vdg::NAME), public
# headers in include/vdg/NAME/. Every module is installed and exported: `cmake --install` puts the
# library, its headers and the vdg CMake package (vdg::NAME) and vdg.pc into the prefix.
#   DEPS          public: other vdg modules, and libraries whose headers vdg's headers include
#   PRIVATE_DEPS  used by the .cpp files only; header-only ones stay out of the installed package,
#                 the others are still needed when a user links the static library, so the
#                 package config finds them.
function(vdg_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(vdg_${name} STATIC ${ARG_SOURCES})
  add_library(vdg::${name} ALIAS vdg_${name})
  set_target_properties(vdg_${name} PROPERTIES EXPORT_NAME ${name})
  if(VDG_BUILD_PYTHON)
    # The Python module (python/) is a shared object that links these static libraries: their code
    # must be position-independent. Only the libraries: the executables keep the compiler's default
    # (PIE), which the tests' precompiled header was built with.
    set_target_properties(vdg_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  target_include_directories(vdg_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
                                                $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set(private_deps "")
  set(installed_deps ${ARG_DEPS})
  foreach(dep IN LISTS ARG_PRIVATE_DEPS)
    _vdg_is_header_only(${dep} header_only)
    if(header_only)
      list(APPEND private_deps $<BUILD_INTERFACE:${dep}>)
    else()
      list(APPEND private_deps ${dep})
      list(APPEND installed_deps ${dep})
    endif()
  endforeach()
  target_link_libraries(vdg_${name} PUBLIC ${ARG_DEPS} PRIVATE ${private_deps})
  vdg_target_defaults(vdg_${name})

  # Record what the installed package must find: external targets, not vdg's own modules.
  foreach(dep IN LISTS installed_deps)
    if(TARGET ${dep} AND NOT dep MATCHES "^vdg::")
      _vdg_package_of(${dep} find pc)
      set_property(GLOBAL APPEND PROPERTY VDG_PACKAGE_FIND "${find}")
      if(pc)
        set_property(GLOBAL APPEND PROPERTY VDG_PACKAGE_PC_REQUIRES ${pc})
      endif()
    elseif(IS_ABSOLUTE "${dep}" AND dep MATCHES "/lib([^/]+)\\.(so|a)$")
      # A library found by path (OpenVDB, whose CMake module Debian cannot load): the CMake package
      # carries the path itself; vdg.pc names it with -l.
      set_property(GLOBAL APPEND PROPERTY VDG_PACKAGE_PC_LIBS "-l${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY VDG_INSTALLED_MODULES ${name})

  install(TARGETS vdg_${name} EXPORT vdgTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  if(EXISTS ${PROJECT_SOURCE_DIR}/include/vdg/${name})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/vdg/${name} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vdg
            FILES_MATCHING PATTERN "*.h")
  endif()
endfunction()

# After every module: the version header, the exported CMake package (vdgConfig.cmake,
# vdgConfigVersion.cmake, vdgTargets.cmake) and vdg.pc, all relocatable (found relative to
# where they are installed, so `cmake --install --prefix ANY` works).
function(vdg_install_package)
  include(CMakePackageConfigHelpers)
  set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/vdg)
  install(FILES ${PROJECT_BINARY_DIR}/include/vdg/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vdg)
  install(EXPORT vdgTargets NAMESPACE vdg:: DESTINATION ${config_dir})

  get_property(modules GLOBAL PROPERTY VDG_INSTALLED_MODULES)
  get_property(finds GLOBAL PROPERTY VDG_PACKAGE_FIND)
  get_property(pc_requires GLOBAL PROPERTY VDG_PACKAGE_PC_REQUIRES)
  list(REMOVE_DUPLICATES finds)
  list(REMOVE_DUPLICATES pc_requires)
  list(JOIN finds "\n" VDG_FIND_DEPENDENCIES)
  set(VDG_MODULE_LIST "${modules}")
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vdgConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/package/vdgConfig.cmake INSTALL_DESTINATION ${config_dir})
  # 0.x: a minor version may break the API, so only the same MAJOR.MINOR is compatible.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/vdgConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/package/vdgConfig.cmake ${PROJECT_BINARY_DIR}/package/vdgConfigVersion.cmake
          DESTINATION ${config_dir})

  # vdg.pc: the libraries are static, so everything they link goes into Requires/Libs (not the
  # .private fields, which plain `pkg-config --libs` leaves out); modules are listed top first,
  # the order a static link needs.
  set(libs "")
  list(REVERSE modules)
  foreach(module IN LISTS modules)
    string(APPEND libs " -lvdg_${module}")
  endforeach()
  get_property(pc_libs GLOBAL PROPERTY VDG_PACKAGE_PC_LIBS)
  list(REMOVE_DUPLICATES pc_libs)
  foreach(lib IN LISTS pc_libs)
    string(APPEND libs " ${lib}")
  endforeach()
  list(JOIN pc_requires " " VDG_PC_REQUIRES)
  set(VDG_PC_LIBS "${libs}")
  file(RELATIVE_PATH VDG_PC_PREFIX_FROM_PCDIR /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
  string(REGEX REPLACE "/$" "" VDG_PC_PREFIX_FROM_PCDIR "${VDG_PC_PREFIX_FROM_PCDIR}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/vdg.pc.in ${PROJECT_BINARY_DIR}/package/vdg.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/package/vdg.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()

# vdg_add_test(NAME SOURCES ... DEPS ...): a GoogleTest executable registered with CTest.
# Every test program reuses one precompiled header (tests/support/precompiled.h: GoogleTest, Eigen,
# the standard library), built by vdg_test_pch with the same flags; it saves about 40% of a test
# file's compile time. VDG_PCH=OFF compiles each file on its own (to check its includes).
option(VDG_PCH "Precompile the common headers of the test programs" ON)
function(_vdg_test_pch)
  if(TARGET vdg_test_pch)
    return()
  endif()
  add_library(vdg_test_pch STATIC ${PROJECT_SOURCE_DIR}/tests/support/precompiled.cpp)
  target_link_libraries(vdg_test_pch PRIVATE Eigen3::Eigen GTest::gtest)
  target_compile_definitions(vdg_test_pch PRIVATE VDG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  vdg_target_defaults(vdg_test_pch TEST_CODE)
  set_target_properties(vdg_test_pch PROPERTIES UNITY_BUILD OFF)
  # An unusable header is an error, not a silent fall-back to the slow path.
  target_compile_options(vdg_test_pch PUBLIC -Winvalid-pch)
  target_precompile_headers(vdg_test_pch PRIVATE ${PROJECT_SOURCE_DIR}/tests/support/precompiled.h)
endfunction()

function(vdg_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE VDG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  vdg_target_defaults(${name} TEST_CODE)
  set_target_properties(${name} PROPERTIES UNITY_BUILD OFF)  # the precompiled header instead
  if(VDG_PCH)
    _vdg_test_pch()
    # GCC 12 reports an out-of-bounds or overflowing memcpy in std::string's operator+ once it is
    # inlined into a test body (-Warray-bounds, -Wstringop-overflow on libstdc++'s char_traits::copy:
    # known false positives of GCC 12's string code) in a few test files when their headers come
    # precompiled, which changes the inlining. Test programs only, and only that compiler.
    target_compile_options(${name} PRIVATE -Winvalid-pch
      $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-array-bounds -Wno-stringop-overflow -Wno-restrict>)
    target_precompile_headers(${name} REUSE_FROM vdg_test_pch)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ENVIRONMENT "VDG_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
