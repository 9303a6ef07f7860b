/* core_stb: the implementations of stb_image and stb_image_write, in a file
 * of their own so that third-party code gets its own flags: its warnings are
 * not ours to fix, and its JPEG writer shifts negative ints (UBSan
 * "left shift of 16369664 by 8 places", stb_image_write.h), so this file is
 * built with -fno-sanitize=shift (src/core/CMakeLists.txt). */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#pragma GCC diagnostic ignored "-Wshadow"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_TGA
#define STBI_FAILURE_USERMSG
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#pragma GCC diagnostic pop
