// libFuzzer harness: the native network reader, then the whole G¹ pipeline.
#include <cstdint>
#include <string>

#include "curvenet/io.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  const std::string text(reinterpret_cast<const char *>(data), size);
  curvenet::NetworkDescription description;
  try {
    description = curvenet::parseNetworkJson(text, "fuzz.json");
  } catch (const curvenet::InputError &) {
    return 0;
  }
  curvenet::fuzz::exercise(description);
  return 0;
}
