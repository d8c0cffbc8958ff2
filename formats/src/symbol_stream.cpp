// Draco's symbol coder behind put_symbols/get_symbols; the only Draco headers the
// predictive codec needs.
#include "symbol_stream.h"

#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/compression/entropy/symbol_encoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/draco_version.h>
#include <draco/core/encoder_buffer.h>

#include <stdexcept>
#include <string>

namespace crowdbake::pack_io {

void put_symbols(ByteWriter& out, const std::vector<uint32_t>& symbols, int components) {
  if (symbols.empty()) {
    out.u32(0);
    return;
  }
  // note: Draco picks raw (a table per symbol value) or tagged (bit lengths, then the bits)
  // from an estimate that leaves out the raw table's own size, which dominates for sparse
  // 16-bit residuals; both are tried and the smaller kept (the stream says which).
  // note: raw coding refuses a stream of more than 2^18 distinct values (a hero mesh's
  // triangle streams reach that from about 2M triangles); tagged coding takes any.
  draco::EncoderBuffer best;
  for (const draco::SymbolCodingMethod method :
       {draco::SYMBOL_CODING_TAGGED, draco::SYMBOL_CODING_RAW}) {
    draco::Options options;
    draco::SetSymbolEncodingCompressionLevel(&options, 10);
    draco::SetSymbolEncodingMethod(&options, method);
    draco::EncoderBuffer buffer;
    if (!draco::EncodeSymbols(symbols.data(), static_cast<int>(symbols.size()), components,
                              &options, &buffer))
      continue;
    if (best.size() == 0 || buffer.size() < best.size()) best = std::move(buffer);
  }
  if (best.size() == 0)
    throw std::runtime_error("Draco's symbol coder failed on " + std::to_string(symbols.size()) +
                             " symbols");
  out.u32(static_cast<uint32_t>(best.size()));
  out.raw(best.data(), best.size());
  out.zero_pad(4);
}

bool get_symbols(ByteReader& in, std::vector<uint32_t>& symbols, size_t count, int components,
                 uint32_t limit, const char* field) {
  uint32_t size = 0;
  if (!in.u32(size, field)) return false;
  symbols.assign(count, 0);
  if (count == 0) return size == 0 || in.fail(std::string(field) + ": bytes for an empty stream");
  const uint8_t* data = in.cursor();
  if (!in.skip(size, field)) return false;
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  buffer.set_bitstream_version(DRACO_BITSTREAM_VERSION(draco::kDracoMeshBitstreamVersionMajor,
                                                       draco::kDracoMeshBitstreamVersionMinor));
  if (!draco::DecodeSymbols(static_cast<uint32_t>(count), components, &buffer, symbols.data()))
    return in.fail(std::string(field) + ": Draco's symbol decoder rejected the stream");
  for (size_t i = 0; i < count; ++i)
    if (symbols[i] >= limit)
      return in.fail(std::string(field) + ": symbol " + std::to_string(i) + " is " +
                     std::to_string(symbols[i]) + ", at most " + std::to_string(limit - 1));
  return in.zero_pad(4, field);
}

}  // namespace crowdbake::pack_io
