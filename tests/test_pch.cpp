// The object that owns the tests' shared precompiled header (tests/CMakeLists.txt); no code.
