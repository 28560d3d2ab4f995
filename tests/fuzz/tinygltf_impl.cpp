// tinygltf's implementation, compiled from Debian's header (libtinygltf-dev) into the glTF harness
// instead of linking Debian's library, so that it is instrumented like the rest. Without its
// stb_image reader and writer (TINYGLTF_NO_STB_IMAGE and _WRITE, defined for every harness so that
// all agree on the header): io/gltf_model.h hands pictures to the renderer's own decoder.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
