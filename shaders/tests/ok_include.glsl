// ok_include.glsl: a small include used by the shader preprocessor tests.
const float TEST_INCLUDED = 1.0;
