// The empty object that owns a precompiled header: the product's (product_pch.cmake) and the
// tests' (tests/CMakeLists.txt, thx_test_pch); no code.
