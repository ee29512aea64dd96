# docs/findings.md is the catalogue `vesselid findings` prints (engine/base/finding.cc), under
# its heading: a kind added, removed or reworded in the code without the docs fails here.
# Run as `cmake -DBINARY=<vesselid> -DDOC=<docs/findings.md> -P findings_doc_check.cmake`.
execute_process(COMMAND ${BINARY} findings OUTPUT_VARIABLE catalogue RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "vesselid findings exited ${status}")
endif()
file(READ ${DOC} doc)
string(FIND "${doc}" "${catalogue}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${DOC} does not hold the catalogue `vesselid findings` prints; "
                      "regenerate it: build/vesselid findings")
endif()
