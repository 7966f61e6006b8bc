// The mcap container reader on arbitrary bytes, every message decoded with the definition
// its topic carries: the outcome is messages or an odocal::Error naming the file and offset.

#include "bag_fuzz_support.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  odocal::fuzz::expect_only_odocal_errors([&] {
    odocal::fuzz::DecodingVisitor visitor;
    odocal::bag::read_mcap({data, size}, "fuzz-input", visitor);
  });
  return 0;
}
