# cmake --install of the build into a scratch prefix, then the consumer project configured with
# find_package(sketchsurf), built and run on a sketch, and sketchsurf.pc asked for its flags.
# Run as: cmake -DBUILD_DIR=... -DWORK_DIR=... -DCONSUMER_DIR=... -DSKETCH=... -DSTROKES=N
#               -P install_test.cmake
cmake_minimum_required(VERSION 3.25)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${ARGN} failed (${status}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")

foreach(expected include/sketchsurf/surfacing/pipeline.h include/sketchsurf/surfacing/sketch/io/sketch_io.h)
  if(NOT EXISTS "${prefix}/${expected}")
    message(FATAL_ERROR "not installed: ${expected}")
  endif()
endforeach()
file(GLOB_RECURSE headers "${prefix}/include/*.h")
foreach(header IN LISTS headers)
  file(STRINGS "${header}" ceres REGEX "#include <ceres/")
  if(ceres)
    message(FATAL_ERROR "${header} includes Ceres, which the installed libraries do not link")
  endif()
endforeach()
file(GLOB_RECURSE config "${prefix}/*/sketchsurfConfig.cmake")
file(GLOB_RECURSE version "${prefix}/*/sketchsurfConfigVersion.cmake")
file(GLOB_RECURSE pc "${prefix}/*/pkgconfig/sketchsurf.pc")
file(GLOB_RECURSE archives "${prefix}/*/libsketchsurf_*.a")
list(LENGTH archives archive_count)
if(NOT config OR NOT version OR NOT pc OR archive_count LESS 7)
  message(FATAL_ERROR "incomplete install: config [${config}] version [${version}] pc [${pc}] "
                      "libraries [${archives}]")
endif()

run("${CMAKE_COMMAND}" -S "${CONSUMER_DIR}" -B "${WORK_DIR}/consumer" -G Ninja
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/consumer" "${SKETCH}" "${WORK_DIR}/copy.json")
if(NOT out MATCHES "^${STROKES} strokes")
  message(FATAL_ERROR "the consumer read the sketch as '${out}', expected ${STROKES} strokes")
endif()

find_program(PKG_CONFIG pkg-config REQUIRED)
get_filename_component(pc_dir "${pc}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
run("${PKG_CONFIG}" --cflags --libs sketchsurf)
file(REAL_PATH "${prefix}/include/sketchsurf" include_dir)
if(NOT out MATCHES "-I[^ ]*include/sketchsurf" OR NOT out MATCHES "-lsketchsurf_core")
  message(FATAL_ERROR "pkg-config --cflags --libs sketchsurf gave '${out}'")
endif()
execute_process(COMMAND "${PKG_CONFIG}" --variable=includedir sketchsurf OUTPUT_VARIABLE pc_include
                OUTPUT_STRIP_TRAILING_WHITESPACE)
file(REAL_PATH "${pc_include}/sketchsurf" pc_include)
if(NOT pc_include STREQUAL include_dir)
  message(FATAL_ERROR "sketchsurf.pc's includedir is ${pc_include}, the headers are in ${include_dir}")
endif()
message(STATUS "installed, found, built and ran against ${prefix}")
