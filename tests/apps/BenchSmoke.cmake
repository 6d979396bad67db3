# Runs fascia-bench (FASCIA_BENCH) on a small TLED hexahedral cube of two element blocks: it must exit
# with 0 and print its JSON line with the step, single-step and force-field-alone figures and the
# bytes of the layout, and the 1- and 2-thread positions must agree. Then a tetrahedral cube with
# the reference kernel beside TLED and the competitor of --contend, and both force fields in mixed
# precision. A smoke test, not a timing.

# runs fascia-bench with the arguments after `regex` and fails unless it exits with 0 and its
# output matches regex
function(bench_matches regex)
  execute_process(COMMAND ${FASCIA_BENCH} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fascia-bench ${ARGN} exited with ${rc}:\n${out}\n${err}")
  endif()
  if(NOT out MATCHES "${regex}")
    message(FATAL_ERROR "unexpected output of fascia-bench ${ARGN}:\n${out}\n${err}")
  endif()
endfunction()

bench_matches("\"elements\": 729, .*\"median_step_ms\": [0-9.]+, \"p90_step_ms\": [0-9.]+, \"p99_step_ms\": [0-9.]+.*\"ns_per_element_step\": [0-9.]+, \"steps_per_s\": [0-9]+, \"element_steps_per_s\": [0-9.e+]+, \"forcefield_ns_per_element\": [0-9.]+, \"bytes_per_element_step\": [0-9.]+, .*\"bitwise_identical_1_vs_2_threads\": true}"
  --forcefield TLED --material NeoHookean --cube 9 --element hexahedra --steps 3 --repeat 1 --determinism)

bench_matches("^{\"forcefield\": \"reference\", \"material\": \"NeoHookean\", .*\"elements\": 384, .*\"contend\": true, \"contend_core\": -?[0-9]+, \"contend_cpu_s\": [0-9.]+}\n{\"forcefield\": \"TLED\", .*\"elements\": 384, .*\"step_time_vs_first\": [0-9.]+, .*\"contend\": true"
  --forcefield TLED --material NeoHookean --cube 4 --steps 20 --repeat 2 --reference --contend)

# --precision mixed reaches the force field (both), and the 1- and 2-thread positions still agree
bench_matches("\"forcefield\": \"HEML\", .*\"precision\": \"mixed\", .*\"bitwise_identical_1_vs_2_threads\": true}"
  --forcefield HEML --cube 6 --steps 3 --repeat 1 --precision mixed --determinism)
bench_matches("\"forcefield\": \"TLED\", .*\"precision\": \"mixed\", .*\"bitwise_identical_1_vs_2_threads\": true}"
  --forcefield TLED --material NeoHookean --cube 6 --steps 3 --repeat 1 --precision mixed --determinism)
# an unknown precision is refused
execute_process(COMMAND ${FASCIA_BENCH} --precision single RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT err MATCHES "--precision is double or mixed")
  message(FATAL_ERROR "fascia-bench --precision single: exit ${rc}, ${err}")
endif()
# --node-buffers reaches TLED's scene (both layouts run, the same bits on 1 and 2 threads), and an
# unknown layout is refused
bench_matches("\"forcefield\": \"TLED\", .*\"node_buffers\": \"compact\", .*\"bitwise_identical_1_vs_2_threads\": true}"
  --forcefield TLED --material NeoHookean --cube 6 --steps 3 --repeat 1 --node-buffers compact --determinism)
execute_process(COMMAND ${FASCIA_BENCH} --node-buffers wide RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT err MATCHES "--node-buffers is auto, range or compact")
  message(FATAL_ERROR "fascia-bench --node-buffers wide: exit ${rc}, ${err}")
endif()
# --device: the device path of the bench (a CudaStep in the root node, one wait per timed window,
# the bytes of the device layout) through CudaStep's emulation where the cuda plugin is built; on
# --device cuda without a GPU, the located error of CudaStep (exit 2), never a CPU figure; an
# unknown device and a CPU precision on the device refused
if(FASCIA_CUDA)
  bench_matches("\"forcefield\": \"TLED\", .*\"elements\": 384, .*\"precision\": \"float\", \"device\": \"emulate\", .*\"element_steps_per_s\": [0-9.e+]+, \"bytes_per_element_step\": [0-9.]+, "
    --forcefield TLED --material NeoHookean --cube 4 --steps 20 --repeat 1 --device emulate --precision float)
  bench_matches("\"forcefield\": \"HEML\", .*\"elements\": 384, .*\"precision\": \"double\", \"device\": \"emulate\", .*\"element_steps_per_s\": [0-9.e+]+, \"bytes_per_element_step\": [0-9.]+, "
    --forcefield HEML --material NeoHookean --cube 4 --steps 20 --repeat 1 --device emulate)
  bench_matches("\"device\": \"emulate\", \"force_order\": \"node\", .*\"element_steps_per_s\": [0-9.e+]+, "
    --forcefield TLED --material NeoHookean --cube 4 --steps 20 --repeat 1 --device emulate --cuda-forces node)
  execute_process(COMMAND ${FASCIA_BENCH} --forcefield TLED --cube 4 --steps 5 --repeat 1 --device cuda
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT (rc EQUAL 0 AND out MATCHES "\"device\": \"cuda\"") AND NOT (rc EQUAL 2 AND err MATCHES "CudaStep.*no usable CUDA device"))
    message(FATAL_ERROR "fascia-bench --device cuda: exit ${rc}, ${out} ${err}")
  endif()
endif()
foreach(args "--device;opencl" "--device;cuda;--forcefield;TLED;--precision;mixed" "--device;cuda;--contend")
  execute_process(COMMAND ${FASCIA_BENCH} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "fascia-bench: --(device|precision)")
    message(FATAL_ERROR "fascia-bench ${args}: exit ${rc}, ${err}")
  endif()
endforeach()
execute_process(COMMAND ${FASCIA_BENCH} --cuda-block 128 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 1 OR NOT err MATCHES "fascia-bench: --cuda-block and --cuda-forces need --device")
  message(FATAL_ERROR "fascia-bench --cuda-block without --device: exit ${rc}, ${err}")
endif()
execute_process(COMMAND ${FASCIA_BENCH} --device emulate --cuda-forces slots RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 1 OR NOT err MATCHES "fascia-bench: --cuda-forces is element or node")
  message(FATAL_ERROR "fascia-bench --cuda-forces slots: exit ${rc}, ${err}")
endif()
