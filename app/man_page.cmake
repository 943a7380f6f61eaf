# Writes OUT (the manual page, roff) and OUT.gz from PROGRAM's own tables: `PROGRAM keys --format
# man`. Run after each link: cmake -DPROGRAM=... -DOUT=... -P this-file.
execute_process(COMMAND "${PROGRAM}" keys --format man OUTPUT_FILE "${OUT}.tmp"
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} keys --format man failed (${rc}): ${err}")
endif()
file(RENAME "${OUT}.tmp" "${OUT}")
# -n: no name or time stamp inside, so the same page compresses to the same bytes.
execute_process(COMMAND gzip -9 -n -c "${OUT}" OUTPUT_FILE "${OUT}.gz" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gzip of ${OUT} failed (${rc})")
endif()
