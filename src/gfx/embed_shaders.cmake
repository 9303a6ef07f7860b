# embed_shaders: writes OUT, the C source of gfx's embedded shader table
# (gfx_shader_files, declared in gfx_local.h): every GLSL file under
# SHADER_DIR (.glsl and the stage extensions) as a string literal, by its
# path relative to SHADER_DIR, sorted. Run at build time by
# src/gfx/CMakeLists.txt:
#   cmake -DSHADER_DIR=<source>/shaders -DOUT=<file.c> -P embed_shaders.cmake
if(NOT SHADER_DIR OR NOT OUT)
  message(FATAL_ERROR "embed_shaders.cmake: pass -DSHADER_DIR=... -DOUT=...")
endif()

set(globs)
foreach(ext glsl comp vert frag geom tesc tese)
  list(APPEND globs "${SHADER_DIR}/*.${ext}")
endforeach()
file(GLOB_RECURSE files RELATIVE "${SHADER_DIR}" ${globs})
list(SORT files)

set(body "")
set(count 0)
foreach(rel IN LISTS files)
  file(READ "${SHADER_DIR}/${rel}" text)
  file(SIZE "${SHADER_DIR}/${rel}" size)
  # One C string literal: backslashes, quotes, control characters and
  # '?' (trigraphs: -std=c11) escaped, one source line per literal line.
  string(REPLACE "\\" "\\\\" text "${text}")
  string(REPLACE "\"" "\\\"" text "${text}")
  string(REPLACE "?" "\\?" text "${text}")
  string(REPLACE "\t" "\\t" text "${text}")
  string(REPLACE "\r" "\\r" text "${text}")
  string(REPLACE "\n" "\\n\"\n     \"" text "${text}")
  string(APPEND body "    {\"${rel}\", ${size},\n     \"${text}\"},\n")
  math(EXPR count "${count} + 1")
endforeach()

if(count EQUAL 0)
  message(FATAL_ERROR "embed_shaders.cmake: no shaders under ${SHADER_DIR}")
endif()
file(WRITE "${OUT}"
  "/* gfx_shaders_embedded: generated at build time by src/gfx/embed_shaders.cmake\n"
  " * from ${SHADER_DIR}; do not edit. */\n"
  "#include \"gfx/gfx_local.h\"\n\n"
  "const int gfx_shader_file_count = ${count};\n"
  "const gfx_shader_file_t gfx_shader_files[] = {\n${body}};\n")
