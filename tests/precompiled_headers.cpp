// The anchor of the tests' precompiled headers (tests/CMakeLists.txt, PBM_TEST_PCH): compiled
// once with them, so that every test reuses them.
