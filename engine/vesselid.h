// The vesselid library: everything a program needs to identify a motion model by output
// error, one stage or a staged run. Include this header only; the headers it lists are the
// public API, every other header under engine/ is internal and may change.
//
//   1. a model: a plain struct with a templated right-hand side (model/model.h), wrapped by
//      MakeModelHandle (model/model_handle.h); problems/ holds the shipped families;
//   2. experiments: recorded data (data/trajectory.h), from a CSV file or in memory
//      (ExperimentSpec::table, data/trajectory_table.h), mapped onto the model's inputs and
//      outputs by an ExperimentSpec and BuildExperiment (model/experiment.h);
//   3. one stage: OutputErrorProblem::Create (solve/output_error_problem.h) and RunStage
//      (solve/stage.h), or RunLeastSquares (regression/least_squares.h) and RunStepRegression
//      (step_regression/step_regression.h) for the equation-error starts;
//   4. a staged run: a RunConfig (run/run_config.h), filled in C++ or loaded from YAML
//      (config/config.h), run and judged by Identify (diagnose/run_findings.h) into a
//      RunResult (run/run_result.h) with its findings and verdict, written by WriteRunResults
//      (report/results_writer.h) or taken as results.json's text (output/results_json_text.h)
//      and traces (output/run_traces.h);
//   5. studies of a stage (study/study.h).
//
// examples/identify_zigzag.cc runs one stage, examples/staged_run.cc a staged run without
// YAML.
#pragma once

// Models and simulation.
#include "engine/model/damping_inertia_form.h"
#include "engine/model/model.h"
#include "engine/model/model_handle.h"
#include "engine/model/open_loop_simulation.h"
#include "engine/model/regression_form.h"
#include "engine/model/rk4.h"

// Recorded experiments.
#include "engine/data/trajectory.h"
#include "engine/data/trajectory_table.h"
#include "engine/model/experiment.h"

// One output-error stage: the problem, its solvers and what they report.
#include "engine/solve/covariance.h"
#include "engine/solve/global_start.h"
#include "engine/solve/local_analysis.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/parameter.h"
#include "engine/solve/progress.h"
#include "engine/solve/stage.h"

// Equation-error stages.
#include "engine/regression/least_squares.h"
#include "engine/step_regression/step_regression.h"

// Staged runs.
#include "engine/run/fusion.h"
#include "engine/run/pipeline.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

// The judgement of a run: typed findings and verdicts; Identify runs and judges.
#include "engine/base/finding.h"
#include "engine/diagnose/run_findings.h"

// Studies and outputs.
#include "engine/report/report_html.h"
#include "engine/output/results_json_text.h"
#include "engine/output/results_text.h"
#include "engine/output/run_traces.h"
#include "engine/report/results_writer.h"
#include "engine/study/study.h"

// Config files and model families.
#include "engine/config/config.h"
#include "engine/config/model_registry.h"

// Structure selection by cross-validation over runs.
#include "engine/select/selection.h"
#include "engine/select/selection_config.h"
