// tinygltf's parser, compiled from Debian's header into the fuzz tree only, with the fuzzer's
// instrumentation (the prebuilt libtinygltf the engine normally links is not instrumented, so libFuzzer
// would see no coverage inside it). CMakeLists.txt here leaves stb_image out.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
