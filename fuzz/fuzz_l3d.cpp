// libFuzzer target "l3d": see its function in fuzz/Targets.h.
#include "fuzz/Targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    candela::fuzz::l3d(data, size);
    return 0;
}
