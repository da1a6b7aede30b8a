// tinyobjloader's implementation compiled into fuzz_obj and fuzz_mtl, so that libFuzzer sees its coverage and
// AddressSanitizer checks its memory accesses (the Debian shared library is not instrumented; the
// executable's definitions take precedence over the library's at link time). Same header, same
// options (float real_t) as the library vdg links.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
