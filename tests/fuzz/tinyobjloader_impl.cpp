// tinyobjloader's implementation, compiled from Debian's header (libtinyobjloader-dev) into the
// OBJ harnesses instead of linking Debian's library, so that it is instrumented like the rest.
// Debian builds the library with float coordinates (real_t = float), as this does.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
