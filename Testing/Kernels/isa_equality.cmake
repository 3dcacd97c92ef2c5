# SPDX-License-Identifier: BSD-3-Clause
# Kernels-isa-equality: run the sky kernel's hash program built with its instruction-set clones
# (CLONES) and built for the baseline alone (BASELINE); pass only if both succeed and print the
# same hash for every configuration. Also Kernels-void-skip-equality, whose BASELINE is built
# with AP_HORIZON_NO_VOID_SKIP (WHAT: the failure's message).
foreach (_exe IN ITEMS CLONES BASELINE)
  execute_process(COMMAND "${${_exe}}" RESULT_VARIABLE _rc OUTPUT_VARIABLE _out_${_exe}
    ERROR_VARIABLE _err)
  message("${_exe} (${${_exe}}):\n${_out_${_exe}}${_err}")
  if (NOT _rc EQUAL 0)
    message(FATAL_ERROR "${_exe} failed (${_rc})")
  endif ()
endforeach ()
cmake_host_system_information(RESULT _cpu QUERY PROCESSOR_DESCRIPTION)
message("CPU: ${_cpu}")
if (NOT _out_CLONES STREQUAL _out_BASELINE)
  if (NOT DEFINED WHAT)
    set(WHAT "the kernel's results depend on the instruction set the CPU picked")
  endif ()
  message(FATAL_ERROR "${WHAT}")
endif ()
