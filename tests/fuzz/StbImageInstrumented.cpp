// The texture fuzz target's stb_image: Debian's header (libstb-dev, the snapshot the libstb0 the program links is
// built from) compiled into the target with coverage and AddressSanitizer. Debian's libstb.so is neither, so the
// fuzzer would see nothing inside the decoders and none of their out-of-bounds reads; the executable's definitions
// take the place of the library's. Only for the libFuzzer build (tests/fuzz/CMakeLists.txt).
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
