# A suite for .ci/test_budget's own tests (tests/CMakeLists.txt, test_budget_*): one quick
# test, one deliberately slow one (0.6 s) and one that fails, run by ctest from a copy in the
# build folder.
add_test(quick_test "/bin/true")
add_test(slow_test "/bin/sleep" "0.6")
add_test(failing_test "/bin/false")
