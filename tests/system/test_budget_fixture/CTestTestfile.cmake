# A suite for .ci/test_budget's own test (tests/CMakeLists.txt, test_budget_*): one quick test
# and one deliberately slow one (1.5 s), run by ctest from a copy in the build folder.
add_test(quick_test "/bin/true")
add_test(slow_test "/bin/sleep" "1.5")
