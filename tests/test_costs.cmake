# The slowest tests' seconds, which CTest reads as their COST: with -j2 it starts the costliest
# first, so that a slow test started last does not run on one core while the other idles. On
# a fresh clone CTest has no timings of its own yet (Testing/Temporary/CTestCostData.txt) and
# would start the tests in the order they were declared. Included by CTest after the test
# programs' discovered tests (tests/CMakeLists.txt); a name no longer defined is ignored, so a
# renamed test only loses its place in the queue.
#
# Figures from: `ctest --test-dir build -j2 -LE long` and `-L long` on a quiet two-core
# machine, 2026-12-07 (each test's time beside another; docs/development.md, "CI passes and
# time budgets"). The tests declared by add_test (python_package, the corpus, ...) carry their
# COST where they are declared.
foreach(entry
    # The default suite (over 3 s).
    "CommandLimits.EveryCommandKilledWhilePublishingNeverMixesTwoSets 7"
    "ConfigReference.NamesEveryKeyTheReadersAcceptAndNoOther 6"
    "HostileInput.KilledAtEveryStepOfThePublicationNeverMixesTwoSets 6"
    "VerdictCorpus.GoodRunsAreQuietAndBadRunsAreCalledOut 5"
    "Interrupt.ResumeFinishesAStoppedRun 4"
    "StepRegressionBootstrap.SelectingLambdaAgainBootstrapsTheAsymptoteToo 4"
    "DesignCommand.PlansWithinItsLimitsAndShrinksEveryStandardError 3"
    "IdentifiedModel.InMemoryBootstrapEnsembleIsWhatResultsJsonGives 3"
    "StructureSelection.SameSelectionForAnyThreadCountAndShownEverywhere 3"
    "NomotoConfigs.PatrolNoiseFreeWithGlobalStart 3"
    # The long label (over 30 s, and those moved from the default suite).
    "InputGainConfigs.StaticLeastSquaresThenRefinement 107"
    "MismatchCampaign.DynamicDefaultLawsSpuriousDeadZoneIsNamed 103"
    "MmgKvlcc2Selection.MmgChosenOverEveryNomotoForm 75"
    "ResumeTest.KilledRunResumesToTheUninterruptedResults 69"
    "Scale.TenThousandWindowsOfOneLogRunWithinTheBudget 65"
    "UsvLog.EveryDefectNamedAndTheQuadraticLawFitsWithoutCompensation 59"
    "InputGainConfigs.DynamicLeastSquaresThenRefinement 50"
    "NoiseWeights.LongHundredRunAcceptance 46"
    "ReportHtmlTest.ErunsalHierarchyReportRendersEveryPlot 35"
    "MismatchCampaign.DynamicConfigSaysWhatItKept 33"
    "ErunsalHierarchy.ShippedConfigEndToEnd 32"
    "ManoeuvrePrediction.CargoShipOvershootsAndTurningWithIntervalsHoldTheTruth 7"
    "NoiseWeights.MonteCarloRecoversTheChannelNoiseAndCoversTheTruth 5")
  string(REPLACE " " ";" entry "${entry}")
  list(GET entry 0 name)
  list(GET entry 1 seconds)
  set_tests_properties("${name}" PROPERTIES COST ${seconds})
endforeach()
