// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78, initial value and final xor
// 0xFFFFFFFF): the checksum of every pack chunk and of the header + chunk table.
// crc32c("123456789") == 0xE3069283.
#pragma once

#include <cstddef>
#include <cstdint>

namespace crowdbake::pack_io {

// Extends `crc` (the value returned for the bytes so far; 0 for none) by `size` bytes.
uint32_t crc32c(const void* data, size_t size, uint32_t crc = 0);

}  // namespace crowdbake::pack_io
