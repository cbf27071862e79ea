// The translation unit that builds the test files' precompiled Catch2 header (tests/CMakeLists.txt).
