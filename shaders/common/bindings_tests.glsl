/* bindings_tests.glsl: the binding numbers of the GPU-kernel tests'
 * shaders (shaders/tests), included by those shaders and by their
 * tests/test_*.c alike; only #define lines and comments, so valid C and
 * GLSL (docs/DESIGN.md "Layout"). A kernel reads what it evaluates from
 * IN (and IN2) and writes what the test compares to its CPU reference
 * to OUT. */
#ifndef BINDINGS_TESTS_GLSL
#define BINDINGS_TESTS_GLSL

#define TEST_BIND_IN 0
#define TEST_BIND_OUT 1
#define TEST_BIND_IN2 2
#define TEST_TEX_IN 0

#endif
