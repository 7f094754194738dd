// stb_implementation.cpp - the stb image reader and PNG writer compiled into the wasm32-wasi baker: the
// host build links Debian's libstb, which exists for the host only; the headers carry the code.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
