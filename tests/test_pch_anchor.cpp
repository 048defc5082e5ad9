// The one source of ht_test_pch (tests/CMakeLists.txt): the target exists to compile the test programs'
// precompiled header, which they reuse.
