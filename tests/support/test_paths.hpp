#pragma once
// Where the tests find the program and the data. The paths come from one file generated per build
// folder (tests/CMakeLists.txt, plumekit_test_paths) instead of -D strings, so that a test's object
// file does not depend on where the clone lies and the compiler cache serves it from any clone
// (docs/ci.md). This header is force-included into every test source.
namespace plumekit_test_paths {
const char* exe();         // the plumekit program
const char* data_dir();    // the shipped data (the PLUMEKIT_DATA_DIR cache variable)
const char* test_data();   // tests/data
const char* source_dir();  // the source tree
const char* python();      // the Python with torch and numpy (PLUMEKIT_PYTHON)
}  // namespace plumekit_test_paths

#define PLUMEKIT_EXE (::plumekit_test_paths::exe())
#define PLUMEKIT_DATA_DIR (::plumekit_test_paths::data_dir())
#define PLUMEKIT_TEST_DATA (::plumekit_test_paths::test_data())
#define PLUMEKIT_SOURCE_DIR (::plumekit_test_paths::source_dir())
#define PLUMEKIT_PYTHON (::plumekit_test_paths::python())
