# Runs fascia-bench (FASCIA_BENCH) on a small TLED hexahedral cube of two element blocks: it must exit
# with 0 and print its JSON line with the step and the force-field-alone figures, and the 1- and
# 2-thread positions must agree. A smoke test, not a timing.
execute_process(
  COMMAND ${FASCIA_BENCH} --forcefield TLED --material NeoHookean --cube 9 --element hexahedra --steps 3 --repeat 1
          --determinism
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fascia-bench exited with ${rc}:\n${out}\n${err}")
endif()
if(NOT out MATCHES "\"elements\": 729, .*\"ns_per_element_step\": [0-9.]+, \"forcefield_ns_per_element\": [0-9.]+, \"bitwise_identical_1_vs_2_threads\": true}")
  message(FATAL_ERROR "unexpected fascia-bench output:\n${out}\n${err}")
endif()
