# Driver of the vdg_install test (see CMakeLists.txt here); run with cmake -P and -D arguments.
# Each step stops the test with a message naming what failed.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "vdg_install: ${what} failed (${rc}):\n${ARGN}\n${out}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

run("cmake --install" ${CMAKE_COMMAND} --install ${VDG_BUILD_DIR} --prefix ${prefix})

# 1. find_package(vdg CONFIG), the installed prefix being the only place vdg can come from.
set(consumer_build ${WORK_DIR}/consumer-cmake)
run("configuring the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "-DCMAKE_CXX_FLAGS=${SANITIZE_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE_FLAGS}")
file(STRINGS ${consumer_build}/CMakeCache.txt vdg_dir REGEX "^vdg_DIR:")
string(REGEX REPLACE "^vdg_DIR:[A-Z]+=" "" vdg_dir "${vdg_dir}")
file(REAL_PATH ${prefix} real_prefix)
file(REAL_PATH "${vdg_dir}" vdg_dir)
string(FIND "${vdg_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "vdg_install: the consumer found vdg in ${vdg_dir}, not in the installed prefix ${prefix}")
endif()
run("building the consumer" ${CMAKE_COMMAND} --build ${consumer_build})
run("running the consumer (CMake package)" ${consumer_build}/vdg_consumer)
message(STATUS "${run_output}")
# The model reader alone (vdg::io_model): it runs, and its link line names none of the 3D morphs'
# libraries, which the link line of the consumer of every module does name (so the check can see
# them). The linker may drop unused shared libraries, so the link line is checked, not ldd.
run("running the model consumer (vdg::io_model alone)" ${consumer_build}/vdg_model_consumer)
message(STATUS "${run_output}")
function(link_line target out)
  if(EXISTS ${consumer_build}/CMakeFiles/${target}.dir/link.txt)  # Makefile generators
    file(READ ${consumer_build}/CMakeFiles/${target}.dir/link.txt line)
  else()  # Ninja: the LINK_LIBRARIES of the target's build statement
    file(READ ${consumer_build}/build.ninja ninja)
    string(FIND "${ninja}" "build ${target}:" at)
    if(at LESS 0)
      message(FATAL_ERROR "vdg_install: no link step for ${target} in ${consumer_build}/build.ninja")
    endif()
    string(SUBSTRING "${ninja}" ${at} -1 ninja)
    string(REGEX MATCH "\n  LINK_LIBRARIES = [^\n]*" line "${ninja}")
  endif()
  set(${out} "${line}" PARENT_SCOPE)
endfunction()
# GMP and MPFR are not among them: vdg_viewdep's keys at distances use CGAL's exact predicates too.
set(morph_libraries "openvdb|vdg_morph")
link_line(vdg_consumer all_link)
if(NOT all_link MATCHES "${morph_libraries}")
  message(FATAL_ERROR "vdg_install: the consumer of every module links none of the 3D morphs' libraries, so "
                      "their absence from vdg_model_consumer shows nothing:\n${all_link}")
endif()
link_line(vdg_model_consumer model_link)
if(model_link MATCHES "${morph_libraries}")
  message(FATAL_ERROR "vdg_install: vdg_model_consumer (vdg::io_model alone) links a 3D morph library:\n${model_link}")
endif()

# 2. The same program through pkg-config alone.
set(ENV{PKG_CONFIG_PATH} "")
file(GLOB_RECURSE pc_file ${prefix}/*/vdg.pc)
if(NOT pc_file)
  message(FATAL_ERROR "vdg_install: no vdg.pc installed under ${prefix}")
endif()
get_filename_component(pc_dir "${pc_file}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
run("pkg-config --modversion vdg" ${PKG_CONFIG} --modversion vdg)
string(STRIP "${run_output}" pc_version)
if(NOT pc_version STREQUAL VERSION)
  message(FATAL_ERROR "vdg_install: vdg.pc says version '${pc_version}', the project is ${VERSION}")
endif()
run("pkg-config --cflags --libs vdg" ${PKG_CONFIG} --cflags --libs vdg)
string(STRIP "${run_output}" pc_flags)
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
separate_arguments(sanitize UNIX_COMMAND "${SANITIZE_FLAGS}")
run("compiling the consumer with pkg-config's flags" ${CXX} -std=c++20 ${sanitize} ${CONSUMER_DIR}/main.cpp
    ${pc_flags} -o ${WORK_DIR}/vdg_consumer_pc)
run("running the consumer (pkg-config)" ${WORK_DIR}/vdg_consumer_pc)

# 3. The installed tool reports the project's version.
if(CHECK_TOOL)
  run("installed vdg --version" ${prefix}/bin/vdg --version)
  string(STRIP "${run_output}" tool_version)
  if(NOT tool_version STREQUAL "vdg ${VERSION}")
    message(FATAL_ERROR "vdg_install: installed 'vdg --version' printed '${tool_version}', expected 'vdg ${VERSION}'")
  endif()
  # vdg view's page and runtime are installed beside it (share/vdg/web, found from the tool's prefix).
  foreach(web_file view/index.html view/view.js vdg-three.js)
    if(NOT EXISTS ${prefix}/share/vdg/web/${web_file})
      message(FATAL_ERROR "vdg_install: vdg view's ${web_file} is not installed under ${prefix}/share/vdg/web")
    endif()
  endforeach()
endif()
