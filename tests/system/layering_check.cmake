# The layering rule of engine/: a file includes only its own folder and the folders below it.
#
#   base < data < model < solve < regression < step_regression < run < diagnose < {study, output}
#        < report < config < {export, select} < design < engine/vesselid.h (the public API)
#        < {problems, command}
#        < {cli, fmu}
#
# study and output are siblings (neither includes the other); output holds the result files
# (results.json, report.txt, traces, checkpoints), report the HTML report above them; export
# turns a run's results into a model to take out (model.json, C, FMU). Only the command line
# and the FMU's runtime library (fmu, siblings) may include problems/. command holds the
# commands (run, select, study, simulate, design) the command line and Python both call. Run as `cmake -DROOT=<source tree> -P layering_check.cmake`; every
# upward include is listed as file:line and the script fails if there is one.
if(NOT ROOT)
  message(FATAL_ERROR "layering_check: pass -DROOT=<source tree>")
endif()

set(rank_base 0)
set(rank_data 1)
set(rank_model 2)
set(rank_solve 3)
set(rank_regression 4)
set(rank_step_regression 5)
set(rank_run 6)
set(rank_diagnose 7)
set(rank_study 8)
set(rank_output 8)
set(rank_report 9)
set(rank_config 10)
set(rank_export 11)
set(rank_select 11)
set(rank_design 12)
set(rank_api 13)       # engine/vesselid.h
set(rank_problems 14)
set(rank_command 14)
set(rank_cli 15)
set(rank_fmu 15)

# The layer of a path relative to ROOT ("" when it belongs to none).
function(layer_of path out)
  if(path MATCHES "^engine/vesselid\\.h$")
    set(${out} api PARENT_SCOPE)
  elseif(path MATCHES "^engine/([a-z_]+)/")
    set(${out} ${CMAKE_MATCH_1} PARENT_SCOPE)
  elseif(path MATCHES "^problems/")
    set(${out} problems PARENT_SCOPE)
  else()
    set(${out} "" PARENT_SCOPE)
  endif()
endfunction()

file(GLOB_RECURSE sources RELATIVE ${ROOT} ${ROOT}/engine/*.h ${ROOT}/engine/*.cc
     ${ROOT}/problems/*.h ${ROOT}/problems/*.cc)
set(violations 0)
set(checked 0)
foreach(file IN LISTS sources)
  layer_of(${file} from)
  if(from STREQUAL "" OR NOT DEFINED rank_${from})
    message(SEND_ERROR "${file}: not in a layer folder of engine/ (add the folder to "
                       "layering_check.cmake and docs/development.md)")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  file(STRINGS ${ROOT}/${file} lines)
  set(line_number 0)
  foreach(line IN LISTS lines)
    math(EXPR line_number "${line_number} + 1")
    if(NOT line MATCHES "^#include \"((engine|problems)/[^\"]+)\"")
      continue()
    endif()
    set(target ${CMAKE_MATCH_1})
    math(EXPR checked "${checked} + 1")
    layer_of(${target} to)
    if(to STREQUAL "" OR NOT DEFINED rank_${to})
      message(SEND_ERROR "${file}:${line_number}: includes ${target}, which is in no layer")
      math(EXPR violations "${violations} + 1")
    elseif(NOT to STREQUAL from AND NOT rank_${to} LESS rank_${from})
      message(SEND_ERROR "${file}:${line_number}: ${from} includes ${target} (${to} is not "
                         "below ${from})")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

list(LENGTH sources files)
if(files EQUAL 0)
  message(FATAL_ERROR "layering: no engine/ or problems/ sources under ${ROOT} (pass an "
                      "absolute -DROOT)")
endif()
if(violations GREATER 0)
  message(FATAL_ERROR "layering: ${violations} upward includes in ${files} files")
endif()
message(STATUS "layering: ${checked} includes in ${files} files, none upward")
