// The journal's CRC-32 (serial_bytes.hpp, zlib's since 0.2): the standard
// check value, continuation across pieces, and the byte-table definition the
// journal used before, on random data of every length up to 300 bytes and on
// 1 MB, so that a journal written by an earlier build still reads.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <string>

#include "stickslip/serial_bytes.hpp"

namespace stickslip {
namespace {

std::uint32_t crc32_by_table(std::string_view data, std::uint32_t crc = 0) {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  crc = ~crc;
  for (char ch : data) crc = t[(crc ^ static_cast<std::uint8_t>(ch)) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

TEST(Crc32, IsTheStandardCrcAndTheJournalsEarlierOne) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);  // CRC-32/ISO-HDLC check value
  EXPECT_EQ(crc32(""), 0u);
  EXPECT_EQ(crc32(std::string_view{}, 0x12345678u), 0x12345678u);
  std::mt19937_64 gen(7);
  std::string data;
  for (std::size_t n = 0; n <= 300; ++n) {
    ASSERT_EQ(crc32(data), crc32_by_table(data)) << n << " bytes";
    data.push_back(static_cast<char>(gen()));
  }
  std::string big(1 << 20, '\0');
  for (auto& c : big) c = static_cast<char>(gen());
  EXPECT_EQ(crc32(big), crc32_by_table(big));
  const std::string_view a(big.data(), 12345), b(big.data() + 12345, big.size() - 12345);
  EXPECT_EQ(crc32(b, crc32(a)), crc32(big));  // continued across pieces
}

}  // namespace
}  // namespace stickslip
