# Surfaces SKETCH with the CLI (ARGS: extra surface arguments) into WORK/NAME.glb and .gltf and
# runs the Khronos glTF validator on both (gltf_validate.js); fails on any validator error.
# cmake -DCLI=... -DSKETCH=... "-DARGS=a;b" -DNAME=... -DWORK=... -DNODE=... -DNODE_MODULES=...
#       -DSCRIPT=gltf_validate.js -P gltf_validate.cmake
cmake_minimum_required(VERSION 3.20)
file(MAKE_DIRECTORY "${WORK}")
set(outputs "")
foreach(ext glb gltf)
  set(out "${WORK}/${NAME}.${ext}")
  execute_process(COMMAND "${CLI}" surface "${SKETCH}" ${ARGS} -q -o "${out}" RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "sketchsurf surface ${SKETCH} -o ${out} failed (${status})")
  endif()
  list(APPEND outputs "${out}")
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "NODE_PATH=${NODE_MODULES}" "${NODE}" "${SCRIPT}" ${outputs}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the glTF validator reports errors (${status})")
endif()
