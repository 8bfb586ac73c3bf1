// libFuzzer target "tm33": see its function in fuzz/Targets.h.
#include "fuzz/Targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    candela::fuzz::tm33(data, size);
    return 0;
}
