# Installs the build into a scratch prefix, configures examples/consumer against it with the same
# compiler, sanitizer flags and optimisation (CXX, CXX_FLAGS, OPT_FLAGS: the sanitized build's -O1
# compiles the consumer in half the time of Release's -O3), builds and runs it.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  message("${out}")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_CXX_COMPILER=${CXX}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_CXX_FLAGS_RELEASE=${OPT_FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/gravity_compensation ${WORK_DIR}/prefix/share/tpf/arm4.robot.json)
if(NOT last_output MATCHES "holding currents")
  message(FATAL_ERROR "the consumer did not print its holding currents")
endif()
run(${WORK_DIR}/build/contact_estimation ${WORK_DIR}/prefix/share/tpf)

# The installed tool finds its data beside itself (not in this source tree), simulates a short log
# of the installed twin and identifies a model from it.
set(tool ${WORK_DIR}/prefix/bin/tpf)
set(data ${WORK_DIR}/prefix/share/tpf)
unset(ENV{TPF_DATA_DIR})
execute_process(COMMAND ${tool} evaluate --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
string(FIND "${help}" "${data}/arm4.robot.json" installed_default)
string(FIND "${help}" "${SOURCE_DIR}/data" source_default)
if(NOT rc EQUAL 0 OR installed_default EQUAL -1 OR NOT source_default EQUAL -1)
  message(FATAL_ERROR "the installed tpf does not name its installed data:\n${help}")
endif()
if(EXISTS ${data}/real)
  message(FATAL_ERROR "the measured logs were installed as the core's data: ${data}/real")
endif()
run(${tool} simulate --scenario ${data}/scenarios/excitation.json --duration 30 --quiet
    --out ${WORK_DIR}/excitation.csv)
run(${tool} identify --log ${WORK_DIR}/excitation.csv --robot ${data}/arm4.robot.json --quiet
    --out ${WORK_DIR}/arm4.params.json)
message("installed tpf identified the simulated log")
